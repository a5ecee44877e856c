#include "analysis/coverage_map.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

namespace peensim {

namespace {

// Cells [lo, hi] (inclusive, clamped to [0, dim - 1]) overlapped by [a, b] on one axis; false if none.
bool cell_range(double a, double b, double origin, double cell, std::int64_t dim, std::int64_t& lo, std::int64_t& hi) {
    const double fa = std::floor((a - origin) / cell);
    const double fb = std::floor((b - origin) / cell);
    if (fb < 0.0 || fa > static_cast<double>(dim - 1)) return false;
    lo = static_cast<std::int64_t>(std::max(fa, 0.0));
    hi = static_cast<std::int64_t>(std::min(fb, static_cast<double>(dim - 1)));
    return true;
}

// Edge subdivisions n of a triangle (so n^2 samples): every sub-triangle's edges <= spacing;
// 0 for a degenerate triangle.
int subdivisions(const Vec3& a, const Vec3& b, const Vec3& c, double spacing_m) {
    const Vec3 ab = b - a, ac = c - a;
    if (!(ab.cross(ac).norm() > 0.0)) return 0;
    const double longest = std::max({ab.norm(), ac.norm(), (ac - ab).norm()});
    return std::max(1, static_cast<int>(std::ceil(longest / spacing_m)));
}

}  // namespace

std::int64_t CoverageMap::samples_needed(const TriangleMesh& mesh, double spacing_m) {
    std::int64_t samples = 0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const std::int64_t n = subdivisions(mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2), spacing_m);
        samples += n * n;
    }
    return samples;
}

CoverageMap::CoverageMap(const TriangleMesh& mesh, double spacing_m, double largest_dent_diameter_m) : spacing_(spacing_m) {
    if (!(spacing_m > 0.0) || !(largest_dent_diameter_m > 0.0))
        throw std::invalid_argument("CoverageMap: spacing and largest dent diameter must be positive");
    const std::size_t count = mesh.triangle_count();
    patches_.resize(count);
    std::int64_t samples = 0;
    for (std::size_t t = 0; t < count; ++t) {
        const Vec3& a = mesh.corner(t, 0);
        const Vec3 ab = mesh.corner(t, 1) - a;
        const Vec3 ac = mesh.corner(t, 2) - a;
        const Vec3 cross = ab.cross(ac);
        Patch& p = patches_[t];
        p.origin = a;
        p.area = 0.5 * cross.norm();
        p.first_sample = samples;
        p.n = subdivisions(a, mesh.corner(t, 1), mesh.corner(t, 2), spacing_m);
        if (p.n == 0) continue;  // degenerate: no samples, no area
        p.step_u = ab / p.n;
        p.step_v = ac / p.n;
        p.unit_normal = cross.normalized();
        const Vec3 b = mesh.corner(t, 1), c = mesh.corner(t, 2);
        p.centre = 0.5 * (a.cwiseMin(b).cwiseMin(c) + a.cwiseMax(b).cwiseMax(c));
        p.reach = std::max({(a - p.centre).norm(), (b - p.centre).norm(), (c - p.centre).norm()});
        total_area_ += p.area;
        samples += static_cast<std::int64_t>(p.n) * p.n;
    }
    sample_count_ = samples;
    covered_.assign(static_cast<std::size_t>((samples + 63) / 64), 0);
    covered_count_.assign(count, 0);
    stamp_.assign(count, 0);
    build_grid(mesh, largest_dent_diameter_m);
}

void CoverageMap::build_grid(const TriangleMesh& mesh, double largest_dent_diameter_m) {
    Vec3 lo = Vec3::Constant(0.0), hi = Vec3::Constant(0.0);
    if (!mesh.vertices.empty()) {
        lo = hi = mesh.vertices.front();
        for (const Vec3& v : mesh.vertices) {
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
        }
    }
    grid_min_ = lo;
    const Vec3 extent = hi - lo;
    cell_ = largest_dent_diameter_m;
    for (;;) {
        std::int64_t total = 1;
        for (int k = 0; k < 3; ++k) {
            dims_[k] = static_cast<std::int64_t>(std::floor(extent[k] / cell_)) + 1;
            total *= dims_[k];
        }
        if (total <= kCoverageGridMaxCells) break;
        cell_ *= 1.25;
    }
    const auto cell_index = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
        return static_cast<std::size_t>((z * dims_[1] + y) * dims_[0] + x);
    };
    // Two passes (count, then fill) over the cells each triangle's box overlaps and its plane cuts.
    cell_start_.assign(static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]) + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
        std::vector<std::uint32_t> fill;
        if (pass == 1) {
            for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
            cell_triangles_.assign(cell_start_.back(), 0);
            fill.assign(cell_start_.begin(), cell_start_.end() - 1);
        }
        for (std::size_t t = 0; t < patches_.size(); ++t) {
            const Patch& p = patches_[t];
            if (p.n == 0) continue;
            const Vec3 b = mesh.corner(t, 1), c = mesh.corner(t, 2);
            const Vec3 tlo = p.origin.cwiseMin(b).cwiseMin(c), thi = p.origin.cwiseMax(b).cwiseMax(c);
            std::int64_t r0[3] = {0, 0, 0}, r1[3] = {-1, -1, -1};  // empty unless the box meets the grid
            for (int k = 0; k < 3; ++k) cell_range(tlo[k], thi[k], grid_min_[k], cell_, dims_[k], r0[k], r1[k]);
            // Box-plane test (m), with a margin so a face lying exactly on a cell boundary (common
            // for axis-aligned faces) is not lost to round-off in both neighbouring cells.
            const double half_reach = 0.5 * cell_ * p.unit_normal.cwiseAbs().sum() * (1.0 + 1e-9) + 1e-12;
            for (std::int64_t z = r0[2]; z <= r1[2]; ++z)
                for (std::int64_t y = r0[1]; y <= r1[1]; ++y)
                    for (std::int64_t x = r0[0]; x <= r1[0]; ++x) {
                        const Vec3 centre = grid_min_ + cell_ * Vec3(static_cast<double>(x) + 0.5, static_cast<double>(y) + 0.5,
                                                                     static_cast<double>(z) + 0.5);
                        if (std::abs((centre - p.origin).dot(p.unit_normal)) > half_reach) continue;
                        const std::size_t c_index = cell_index(x, y, z);
                        if (pass == 0)
                            ++cell_start_[c_index + 1];
                        else
                            cell_triangles_[fill[c_index]++] = static_cast<std::uint32_t>(t);
                    }
        }
    }
}

bool CoverageMap::dent_cells(const Vec3& centre, double radius_m, std::int64_t lo[3], std::int64_t hi[3]) const {
    for (int k = 0; k < 3; ++k)
        if (!cell_range(centre[k] - radius_m, centre[k] + radius_m, grid_min_[k], cell_, dims_[k], lo[k], hi[k])) return false;
    if (++dent_stamp_ == 0) {  // wrapped after 2^32 dents: restart the stamps
        std::fill(stamp_.begin(), stamp_.end(), 0u);
        dent_stamp_ = 1;
    }
    return true;
}

void CoverageMap::clear() {
    std::fill(covered_.begin(), covered_.end(), std::uint64_t{0});
    std::fill(covered_count_.begin(), covered_count_.end(), 0);
}

std::int64_t CoverageMap::covered_samples(std::int64_t index, std::int64_t count) const {
    std::int64_t covered = 0;
    for (std::int64_t end = index + count; index < end;) {
        const std::int64_t word = index >> 6, bit = index & 63;
        const std::int64_t n = std::min<std::int64_t>(64 - bit, end - index);
        const std::uint64_t mask = (n == 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << n) - 1)) << bit;
        covered += std::popcount(covered_[static_cast<std::size_t>(word)] & mask);
        index += n;
    }
    return covered;
}

std::int64_t CoverageMap::samples_of_triangle(std::size_t t) const { return static_cast<std::int64_t>(patches_[t].n) * patches_[t].n; }

double CoverageMap::coverage_of_triangle(std::size_t t) const {
    const std::int64_t samples = samples_of_triangle(t);
    return samples == 0 ? 0.0 : static_cast<double>(covered_count_[t]) / static_cast<double>(samples);
}

double CoverageMap::covered_area() const {
    double area = 0.0;
    for (std::size_t t = 0; t < patches_.size(); ++t) area += patches_[t].area * coverage_of_triangle(t);
    return area;
}

double CoverageMap::coverage() const { return total_area_ > 0.0 ? covered_area() / total_area_ : 0.0; }

double CoverageMap::coverage_of(const std::vector<int>& triangles) const {
    double covered = 0.0, total = 0.0;  // m^2
    for (int t : triangles) {
        if (t < 0 || static_cast<std::size_t>(t) >= patches_.size())
            throw std::out_of_range("CoverageMap::coverage_of: triangle index out of range");
        const std::size_t i = static_cast<std::size_t>(t);
        covered += patches_[i].area * coverage_of_triangle(i);
        total += patches_[i].area;
    }
    return total > 0.0 ? covered / total : 0.0;
}

std::size_t CoverageMap::memory_bytes() const {
    return covered_.capacity() * sizeof(std::uint64_t) + patches_.capacity() * sizeof(Patch) +
           covered_count_.capacity() * sizeof(std::int64_t) + stamp_.capacity() * sizeof(std::uint32_t) +
           cell_start_.capacity() * sizeof(std::uint32_t) + cell_triangles_.capacity() * sizeof(std::uint32_t);
}

}  // namespace peensim
