// Regular samples of a triangle: the centroids of the n^2 congruent sub-triangles that dividing each
// edge into n equal parts makes (each stands for area / n^2, so they weigh the triangle exactly).
// The coverage map's scheme (analysis/coverage_map.h); region shares and the reach of facets use it.
#pragma once

#include <algorithm>
#include <cmath>

#include "geometry/triangle_mesh.h"

namespace peensim {

// Subdivisions per edge of triangle t for sub-triangles no longer than spacing_m (m):
// ceil(longest edge / spacing), within [1, max_per_edge].
inline int samples_per_edge(const TriangleMesh& mesh, std::size_t t, double spacing_m, int max_per_edge) {
    double longest = 0.0;
    for (int k = 0; k < 3; ++k) longest = std::max(longest, (mesh.corner(t, (k + 1) % 3) - mesh.corner(t, k)).norm());
    return static_cast<int>(std::clamp(std::ceil(longest / spacing_m), 1.0, static_cast<double>(max_per_edge)));
}

// Calls f(point) for the n^2 sub-triangle centroids of triangle t (n >= 1).
template <class F>
void for_each_sub_centroid(const TriangleMesh& mesh, std::size_t t, int n, F&& f) {
    const Vec3& a = mesh.corner(t, 0);
    const Vec3 u = (mesh.corner(t, 1) - a) / n, v = (mesh.corner(t, 2) - a) / n;
    for (int i = 0; i < n; ++i)
        for (int j = 0; i + j < n; ++j) {
            f(a + (i + 1.0 / 3.0) * u + (j + 1.0 / 3.0) * v);                     // "up" sub-triangle
            if (i + j < n - 1) f(a + (i + 2.0 / 3.0) * u + (j + 2.0 / 3.0) * v);  // "down" sub-triangle
        }
}

}  // namespace peensim
