#include "geometry/mesh_builder.h"

#include <bit>
#include <utility>

namespace peensim {

namespace {

std::uint64_t bits_of(double value) {
    // Adding +0.0 turns -0.0 into +0.0, so the two zeros weld together.
    return std::bit_cast<std::uint64_t>(value + 0.0);
}

std::uint64_t mix(std::uint64_t h) {
    // splitmix64 finaliser: spreads nearby coordinate bit patterns over the whole word.
    h ^= h >> 30;
    h *= 0xbf58476d1ce4e5b9ULL;
    h ^= h >> 27;
    h *= 0x94d049bb133111ebULL;
    h ^= h >> 31;
    return h;
}

}  // namespace

std::size_t MeshBuilder::PositionKeyHash::operator()(const PositionKey& key) const {
    return static_cast<std::size_t>(mix(key[0] ^ mix(key[1] ^ mix(key[2]))));
}

int MeshBuilder::vertex(const Vec3& position_m) {
    const PositionKey key{bits_of(position_m.x()), bits_of(position_m.y()), bits_of(position_m.z())};
    const auto [it, inserted] = vertex_of_position_.try_emplace(key, static_cast<int>(mesh_.vertices.size()));
    if (inserted) mesh_.vertices.push_back(position_m + Vec3::Zero());
    return it->second;
}

void MeshBuilder::reserve(std::size_t triangles) {
    mesh_.triangles.reserve(mesh_.triangles.size() + triangles);
    mesh_.source_facet.reserve(mesh_.source_facet.size() + triangles);
    mesh_.group_of_triangle.reserve(mesh_.group_of_triangle.size() + triangles);
    vertex_of_position_.reserve(vertex_of_position_.size() + triangles / 2 + 3);
    mesh_.vertices.reserve(mesh_.vertices.size() + triangles / 2 + 3);
}

int MeshBuilder::group(const std::string& name) {
    for (std::size_t g = 0; g < mesh_.group_names.size(); ++g) {
        if (mesh_.group_names[g] == name) return static_cast<int>(g);
    }
    mesh_.group_names.push_back(name);
    return static_cast<int>(mesh_.group_names.size() - 1);
}

void MeshBuilder::add_triangle(int a, int b, int c, int source_facet, int group_index) {
    mesh_.triangles.push_back({a, b, c});
    mesh_.source_facet.push_back(source_facet);
    mesh_.group_of_triangle.push_back(group_index);
}

void MeshBuilder::add_triangle(const Vec3& a, const Vec3& b, const Vec3& c, int group_index) {
    const int facet = static_cast<int>(mesh_.triangles.size());
    // One statement each: argument evaluation order is unspecified, vertex numbering must not be.
    const int ia = vertex(a);
    const int ib = vertex(b);
    const int ic = vertex(c);
    add_triangle(ia, ib, ic, facet, group_index);
}

void MeshBuilder::add_quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int group_index) {
    add_triangle(a, b, c, group_index);
    add_triangle(a, c, d, group_index);
}

TriangleMesh MeshBuilder::take() {
    TriangleMesh out = std::move(mesh_);
    mesh_ = TriangleMesh{};
    vertex_of_position_.clear();
    return out;
}

}  // namespace peensim
