#include "analysis/coverage_map.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

namespace peensim {

namespace {

// Sets bits [begin, end) of `words`; returns how many of them were clear before.
std::int64_t set_bits(std::uint64_t* words, std::int64_t begin, std::int64_t end) {
    std::int64_t newly = 0;
    while (begin < end) {
        const std::int64_t word = begin >> 6, bit = begin & 63;
        const std::int64_t count = std::min<std::int64_t>(64 - bit, end - begin);
        const std::uint64_t mask = (count == 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << count) - 1)) << bit;
        newly += std::popcount(mask & ~words[word]);
        words[word] |= mask;
        begin += count;
    }
    return newly;
}

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

void CoverageMap::add_dent(const Vec3& centre, double diameter_m) {
    if (!(diameter_m > 0.0) || patches_.empty()) return;
    const double radius = 0.5 * diameter_m;  // m
    std::int64_t r0[3] = {0, 0, 0}, r1[3] = {-1, -1, -1};
    for (int k = 0; k < 3; ++k)
        if (!cell_range(centre[k] - radius, centre[k] + radius, grid_min_[k], cell_, dims_[k], r0[k], r1[k])) return;
    if (++dent_stamp_ == 0) {  // wrapped after 2^32 dents: restart the stamps
        std::fill(stamp_.begin(), stamp_.end(), 0u);
        dent_stamp_ = 1;
    }
    for (std::int64_t z = r0[2]; z <= r1[2]; ++z)
        for (std::int64_t y = r0[1]; y <= r1[1]; ++y)
            for (std::int64_t x = r0[0]; x <= r1[0]; ++x) {
                const std::size_t c = static_cast<std::size_t>((z * dims_[1] + y) * dims_[0] + x);
                for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
                    const std::uint32_t t = cell_triangles_[k];
                    if (stamp_[t] == dent_stamp_) continue;
                    stamp_[t] = dent_stamp_;
                    if (covered_count_[t] == samples_of_triangle(t)) continue;  // fully covered already
                    cover_patch(t, centre, radius);
                }
            }
}

// Marks the samples of triangle t within radius_m of centre. A sample at grid coordinates (u, v)
// lies at in-plane offset u step_u + v step_v from the corner; inside the dent iff
// G11 u^2 + 2 G12 u v + G22 v^2 - 2 b1 u - 2 b2 v + |w|^2 <= rho^2 (w: the centre projected on the
// plane, rho: radius of the dent sphere's cut through the plane). Per row (v fixed) that is an
// interval of u, found in closed form.
void CoverageMap::cover_patch(std::size_t t, const Vec3& centre, double radius_m) {
    const Patch& p = patches_[t];
    // A dent that cannot reach the triangle's bounding sphere marks nothing: skip the row search
    // (most triangles a dent's cells hold are coplanar neighbours, found by the plane test alone).
    const double reach = p.reach + radius_m;
    if ((centre - p.centre).squaredNorm() > reach * reach) return;
    const Vec3 rel = centre - p.origin;
    const double height = rel.dot(p.unit_normal);               // m
    const double rho2 = radius_m * radius_m - height * height;  // m^2
    if (rho2 <= 0.0) return;
    const Vec3 w = rel - height * p.unit_normal;
    const double g11 = p.step_u.squaredNorm(), g12 = p.step_u.dot(p.step_v), g22 = p.step_v.squaredNorm();
    const double b1 = p.step_u.dot(w), b2 = p.step_v.dot(w);
    const double det = g11 * g22 - g12 * g12;
    const double v_centre = (g11 * b2 - g12 * b1) / det;
    const double v_half = std::sqrt(rho2 * g11 / det);
    const double c0 = w.squaredNorm() - rho2;
    const std::int64_t n = p.n;
    std::int64_t newly = 0;

    // offset 1/3: the "up" samples (rows 0..n-1, row j has n-j); 2/3: the "down" ones (rows 0..n-2).
    for (int kind = 0; kind < 2; ++kind) {
        const double offset = kind == 0 ? 1.0 / 3.0 : 2.0 / 3.0;
        const std::int64_t last_row = kind == 0 ? n - 1 : n - 2;
        const double j_lo = std::max(0.0, std::ceil(v_centre - v_half - offset));
        const double j_hi = std::min(static_cast<double>(last_row), std::floor(v_centre + v_half - offset));
        for (std::int64_t j = static_cast<std::int64_t>(j_lo); j <= static_cast<std::int64_t>(j_hi); ++j) {
            const double v = static_cast<double>(j) + offset;
            const double beta = g12 * v - b1;
            const double gamma = g22 * v * v - 2.0 * b2 * v + c0;
            const double disc = beta * beta - g11 * gamma;
            if (disc < 0.0) continue;
            const double root = std::sqrt(disc);
            const std::int64_t i_last = last_row - j;
            const double i_lo = std::max(0.0, std::ceil((-beta - root) / g11 - offset));
            const double i_hi = std::min(static_cast<double>(i_last), std::floor((-beta + root) / g11 - offset));
            if (i_lo > i_hi) continue;
            const std::int64_t row = p.first_sample + (kind == 0 ? up_row_offset(n, j) : down_row_offset(n, j));
            newly += set_bits(covered_.data(), row + static_cast<std::int64_t>(i_lo), row + static_cast<std::int64_t>(i_hi) + 1);
        }
    }
    covered_count_[t] += newly;
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
