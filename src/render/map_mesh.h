// The mesh an impact map is drawn on. The analysis gives one smoothed value per triangle (at its
// centroid); drawn flat, a coarse mesh's large triangles would show their own outlines again.
// So each triangle is cut into sub-triangles no longer than `spacing_m` (a fraction of the
// smoothing radius: the field varies no faster), and each sub-triangle takes the value linearly
// interpolated, at its centroid, between the triangle's corner values; a corner's value is the
// area-weighted mean of the values of the triangles around its vertex that face the same way
// (normals within 45 deg), so that a sharp edge keeps its two sides apart. A fine mesh (triangles
// already under the spacing) is drawn as it is, each triangle with the mean of its corner values.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "geometry/triangle_mesh.h"

namespace peensim {

struct MapMesh {
    TriangleMesh mesh;           // the sub-triangles, in the original's frame (m)
    std::vector<double> values;  // per sub-triangle (NaN: no data)
};

inline constexpr std::size_t kMaxMapTriangles = 2'000'000;  // sub-triangles at most (the spacing grows to fit)

// values: one per triangle of `mesh` (NaN: no data). Throws std::invalid_argument for a size
// mismatch or a spacing that is not positive.
MapMesh map_mesh(const TriangleMesh& mesh, std::span<const double> values, double spacing_m);

}  // namespace peensim
