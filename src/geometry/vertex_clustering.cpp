#include "geometry/vertex_clustering.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace peensim {

ThinnedMesh cluster_vertices(const TriangleMesh& mesh, double cell_m) {
    ThinnedMesh out;
    out.cell_m = cell_m;
    if (mesh.vertices.empty()) return out;
    Vec3 lo = mesh.vertices.front();
    for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v);
    // Each vertex's cube, packed into 63 bits (21 a side: 2 million cubes an axis).
    const auto cube_of = [&](const Vec3& v) {
        const Vec3 c = ((v - lo) / cell_m).array().floor();
        const auto axis = [](double x) { return static_cast<std::uint64_t>(std::clamp(x, 0.0, 2097151.0)); };
        return axis(c[0]) | axis(c[1]) << 21 | axis(c[2]) << 42;
    };
    std::unordered_map<std::uint64_t, int> cluster_of;  // cube -> merged vertex
    std::vector<int> merged(mesh.vertices.size());
    std::vector<int> members;
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        const auto [it, added] = cluster_of.try_emplace(cube_of(mesh.vertices[i]), static_cast<int>(out.vertices.size()));
        if (added) {
            out.vertices.push_back(Vec3::Zero());
            members.push_back(0);
        }
        merged[i] = it->second;
        out.vertices[static_cast<std::size_t>(it->second)] += mesh.vertices[i];
        ++members[static_cast<std::size_t>(it->second)];
    }
    for (std::size_t k = 0; k < out.vertices.size(); ++k) out.vertices[k] /= members[k];
    std::unordered_set<std::uint64_t> kept;  // the corner triples kept, sorted, against duplicates
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        std::array<int, 3> c;
        for (std::size_t k = 0; k < 3; ++k) c[k] = merged[static_cast<std::size_t>(mesh.triangles[t][k])];
        if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) continue;
        std::array<int, 3> s = c;
        std::sort(s.begin(), s.end());
        const std::uint64_t key = static_cast<std::uint64_t>(s[0]) * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(s[1]) << 21 ^
                                  static_cast<std::uint64_t>(s[2]) << 42;
        if (!kept.insert(key).second) continue;
        out.triangles.push_back(c);
        out.source.push_back(static_cast<std::uint32_t>(t));
    }
    return out;
}

ThinnedMesh thin_for_display(const TriangleMesh& mesh, std::size_t max_triangles) {
    if (mesh.triangle_count() <= max_triangles) {
        ThinnedMesh out;
        out.vertices = mesh.vertices;
        out.triangles = mesh.triangles;
        out.source.resize(mesh.triangle_count());
        for (std::size_t t = 0; t < out.source.size(); ++t) out.source[t] = static_cast<std::uint32_t>(t);
        return out;
    }
    // Start from the cube whose triangles would tile the surface max_triangles times.
    double area = 0.0;  // m2
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
        area += 0.5 * (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0)).norm();
    double cell = std::sqrt(2.0 * area / static_cast<double>(std::max<std::size_t>(1, max_triangles)));
    if (!(cell > 0.0)) cell = 1e-6;
    for (;;) {
        ThinnedMesh out = cluster_vertices(mesh, cell);
        if (out.triangles.size() <= max_triangles) return out;
        cell *= 1.25;
    }
}

}  // namespace peensim
