// Collects triangles into a TriangleMesh, welding vertices by exact position: two corners
// with bit-identical coordinates (+0.0 and -0.0 counted as equal) become one vertex, so a
// surface built from shared coordinate values comes out with shared edges (watertight).
// Used by the mesh loader (positions read from a file) and by every generator.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "geometry/triangle_mesh.h"

namespace peensim {

class MeshBuilder {
public:
    // Index of the vertex at exactly `position_m` (m), adding it if it is new.
    int vertex(const Vec3& position_m);

    // Room for `triangles` more triangles and their vertices (a closed mesh has about half as many
    // vertices as triangles): the vertex map is not rehashed as it grows.
    void reserve(std::size_t triangles);

    // Index of the group with this name, adding it if it is new.
    int group(const std::string& name);

    // Adds triangle (a, b, c) of vertex indices, counter-clockwise seen from its normal side.
    void add_triangle(int a, int b, int c, int source_facet, int group_index);

    // Generator convenience: positions in m, the triangle's facet is its own index (the order
    // in which a writer will store it), group as given.
    void add_triangle(const Vec3& a, const Vec3& b, const Vec3& c, int group_index);
    // Quad a-b-c-d (counter-clockwise seen from its normal side), split along a-c.
    void add_quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int group_index);

    std::size_t triangle_count() const { return mesh_.triangles.size(); }
    const TriangleMesh& mesh() const { return mesh_; }

    // Hands over the mesh; the builder is empty afterwards.
    TriangleMesh take();

private:
    using PositionKey = std::array<std::uint64_t, 3>;
    struct PositionKeyHash {
        std::size_t operator()(const PositionKey& key) const;
    };

    TriangleMesh mesh_;
    std::unordered_map<PositionKey, int, PositionKeyHash> vertex_of_position_;
};

}  // namespace peensim
