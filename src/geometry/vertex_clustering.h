// A mesh thinned for display by vertex clustering: the vertices in one cube of a grid merge into
// their mean, and a triangle whose corners fall into fewer than three cubes (or repeats one kept
// already) is dropped. Each kept triangle remembers the triangle of the mesh it comes from, so a
// per-triangle field carries over by lookup. Coarse but robust on any triangle soup; for looking
// at a part, not for computing on it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/vec.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

struct ThinnedMesh {
    std::vector<Vec3> vertices;                 // m
    std::vector<std::array<int, 3>> triangles;  // into vertices, the orientation of their source
    std::vector<std::uint32_t> source;          // per triangle: the mesh's triangle it comes from
    double cell_m = 0.0;                        // m, the clustering's cube (0: not thinned)
};

// The mesh with vertices merged in cubes of side cell_m (m, > 0).
ThinnedMesh cluster_vertices(const TriangleMesh& mesh, double cell_m);

// The mesh itself when it has at most max_triangles, else clustered with the smallest cube (in
// steps of 25 %) that leaves at most that many.
ThinnedMesh thin_for_display(const TriangleMesh& mesh, std::size_t max_triangles);

}  // namespace peensim
