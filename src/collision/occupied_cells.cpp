#include "collision/occupied_cells.h"

#include <algorithm>
#include <cmath>

#include "collision/cells_near_triangles.h"

namespace peensim {

namespace {

// Of a cell: a query's box is widened by this much on each side before its cells are taken, and a
// cell is marked within this much beyond half its diagonal, so that rounding in the cell indices or
// in the closest point can only mark or count more cells, never fewer.
constexpr double kCellSlack = 1e-6;

}  // namespace

OccupiedCells::OccupiedCells(const TriangleMesh& mesh, double max_cells) {
    if (mesh.triangles.empty() || mesh.vertices.empty()) return;  // no triangle: every box is empty
    Vec3 lo = mesh.vertices.front(), hi = lo;
    for (const Vec3& v : mesh.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const Vec3 extent = hi - lo;
    const double largest = extent.maxCoeff();
    // Cubic cells sized for max_cells over the bounds (a flat mesh's thin axis counted as a
    // thousandth of its largest), widened until the grid with its border of a cell fits.
    const double floor_extent = std::max(largest * 1e-3, 1e-9);
    const Vec3 sized = extent.cwiseMax(Vec3::Constant(floor_extent));
    double cell = std::cbrt(sized.prod() / max_cells);
    if (!(cell > 0.0) || !std::isfinite(cell)) cell = std::max(largest, 1e-3);
    const auto counts = [&](double c) { return ((extent / c).array().floor() + 3.0).matrix(); };
    while (counts(cell).prod() > std::max(max_cells, 64.0)) cell *= 1.1;  // a grid has at least 3 cells a side
    cell_ = cell;
    inv_cell_ = 1.0 / cell;
    origin_ = lo - Vec3::Constant(cell);
    const Vec3 n = counts(cell);
    nx_ = static_cast<std::size_t>(n.x());
    ny_ = static_cast<std::size_t>(n.y());
    nz_ = static_cast<std::size_t>(n.z());

    // Every cell a triangle meets (cells_near_triangles.h), with slack for rounding.
    std::vector<std::uint8_t> marks(nx_ * ny_ * nz_, 0);
    const std::size_t cells_along[3] = {nx_, ny_, nz_};
    mark_cells_near_triangles(
        mesh, origin_, cell_, cells_along, kCellSlack, [&](std::size_t id) { return marks[id] != 0; },
        [&](std::size_t id) { marks[id] = 1; });

    // The summed-volume table, plane by plane.
    const std::size_t sx = nx_ + 1, sy = ny_ + 1;
    sums_.assign(sx * sy * (nz_ + 1), 0);
    for (std::size_t k = 0; k < nz_; ++k)
        for (std::size_t j = 0; j < ny_; ++j) {
            std::uint32_t row = 0;  // marked cells of this row up to i
            for (std::size_t i = 0; i < nx_; ++i) {
                row += marks[(k * ny_ + j) * nx_ + i];
                marked_ += marks[(k * ny_ + j) * nx_ + i];
                // S(i+1, j+1, k+1) = row sum + S(i+1, j, k+1) + S(i+1, j+1, k) - S(i+1, j, k)
                const std::size_t at = ((k + 1) * sy + (j + 1)) * sx + (i + 1);
                sums_[at] = row + sums_[at - sx] + sums_[at - sx * sy] - sums_[at - sx - sx * sy];
            }
        }
}

bool OccupiedCells::any_in(const Vec3& lo, const Vec3& hi) const {
    if (marked_ == 0) return false;
    if (!std::isfinite(lo.sum() + hi.sum())) return true;
    const Vec3 flo = (lo - origin_) * inv_cell_ - Vec3::Constant(kCellSlack);
    const Vec3 fhi = (hi - origin_) * inv_cell_ + Vec3::Constant(kCellSlack);
    const std::size_t n[3] = {nx_, ny_, nz_};
    std::size_t a[3], b[3];  // the box's cells [a, b) along each axis
    for (int k = 0; k < 3; ++k) {
        const double top = static_cast<double>(n[k]);
        if (fhi[k] < 0.0 || flo[k] >= top || flo[k] > fhi[k]) return false;  // beyond the grid, where no triangle is
        a[k] = static_cast<std::size_t>(std::floor(std::max(flo[k], 0.0)));
        b[k] = static_cast<std::size_t>(std::min(std::floor(fhi[k]), top - 1.0)) + 1;
    }
    const std::uint32_t inside = sum(b[0], b[1], b[2]) - sum(a[0], b[1], b[2]) - sum(b[0], a[1], b[2]) - sum(b[0], b[1], a[2]) +
                                 sum(a[0], a[1], b[2]) + sum(a[0], b[1], a[2]) + sum(b[0], a[1], a[2]) - sum(a[0], a[1], a[2]);
    return inside != 0;
}

}  // namespace peensim
