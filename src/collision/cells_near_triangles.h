// The cells of a uniform grid that a mesh's triangles may meet: those whose centre lies within half
// a cell diagonal of a triangle, which every cell a triangle passes through does (a point of the
// triangle in the cell is within half a diagonal of its centre), and a few it only passes near.
// The distance gate (distance_gate.h) and the occupied cells (occupied_cells.h) both start from it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "common/vec.h"
#include "geometry/triangle_mesh.h"
#include "kernels/closest_point.h"

namespace peensim {

// The grid: cell (i, j, k) spans origin + cell_m * [i, i + 1] x [j, j + 1] x [k, k + 1], with
// counts[0..2] cells along x, y, z, indexed (k * ny + j) * nx + i. slack (of a cell, >= 0): marks
// within (1 + slack) half diagonals, so that rounding in the closest point can only mark more.
// is_marked(index): a cell already marked is not tested again; mark(index) marks one.
template <class IsMarked, class Mark>
void mark_cells_near_triangles(const TriangleMesh& mesh, const Vec3& origin, double cell_m, const std::size_t counts[3], double slack,
                               IsMarked&& is_marked, Mark&& mark) {
    const double inv_cell = 1.0 / cell_m;
    const double reach = 0.5 * std::sqrt(3.0) * cell_m * (1.0 + slack);
    const auto index_of = [](double v, std::size_t count) {
        return static_cast<std::size_t>(std::clamp(std::floor(v), 0.0, static_cast<double>(count - 1)));
    };
    const std::size_t nx = counts[0], ny = counts[1], nz = counts[2];
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const Vec3 &a = mesh.corner(t, 0), &b = mesh.corner(t, 1), &c = mesh.corner(t, 2);
        const Vec3 lo = (a.cwiseMin(b).cwiseMin(c) - origin) * inv_cell - Vec3::Constant(0.5 + slack);
        const Vec3 hi = (a.cwiseMax(b).cwiseMax(c) - origin) * inv_cell + Vec3::Constant(0.5 + slack);
        const std::size_t i0 = index_of(lo.x(), nx), i1 = index_of(hi.x(), nx);
        const std::size_t j0 = index_of(lo.y(), ny), j1 = index_of(hi.y(), ny);
        const std::size_t k0 = index_of(lo.z(), nz), k1 = index_of(hi.z(), nz);
        for (std::size_t k = k0; k <= k1; ++k)
            for (std::size_t j = j0; j <= j1; ++j)
                for (std::size_t i = i0; i <= i1; ++i) {
                    const std::size_t id = (k * ny + j) * nx + i;
                    if (is_marked(id)) continue;
                    const Vec3 centre = origin + cell_m * Vec3(i + 0.5, j + 0.5, k + 0.5);
                    if ((closest_point_on_triangle(centre, a, b, c).point - centre).squaredNorm() <= reach * reach) mark(id);
                }
    }
}

}  // namespace peensim
