// Surface coverage (SAE J2277) of one component: which fraction of its area lies inside at least
// one dent. The surface is sampled, each sample stands for a small piece of area, and a dent marks
// the samples within its radius. Pure computation: no file I/O, no printing.
//
// Sampling. Triangle t (corners A, B, C) is cut into n_t^2 congruent sub-triangles by dividing each
// edge into n_t equal parts (n_t = ceil(longest edge / spacing_m), at least 1); one sample sits at
// the centroid of each sub-triangle and carries its area, area_t / n_t^2, so the samples of a
// triangle sum to its area exactly. Every sub-triangle's longest edge -- hence its diameter -- is at
// most spacing_m (= h). Sample positions are never stored: they are recomputed from the triangle
// and the grid index (i, j), and a dent visits only the rows and columns its disc can reach.
//
// Sampling error (flat surface; dents small against the curvature). A sample's area is counted
// wrongly only if its sub-triangle straddles the boundary of the dented region; such a sub-triangle
// lies within h of that boundary. So |covered area - exact covered area| <= 2 h L, where L is the
// length of the boundary of the covered region (L <= sum of dent perimeters, pi d_i each):
//   - one dent of diameter d: relative error of its area <= 2 h pi d / (pi d^2 / 4) = 8 h / d;
//   - N separate dents on area S: |coverage error| <= 2 h N pi d / S.
// This is a worst-case bound; the actual error (errors of opposite sign cancel along the rim) is
// typically 10-100x smaller (tests/analysis/coverage_test.cpp measures it). For dents placed at
// random the estimate is unbiased: every sample point is covered with the same probability as any
// point of the surface, so only the statistical scatter of the dents remains.
//
// Slender triangles. n_t follows the longest edge, so a sliver of length L and height w gets
// (L/h)^2 samples for an area L w / 2: oversampled by ~2 L / w (a 10 mm x 0.25 mm fan triangle by
// ~80x). Correct, but costly in memory; meshes of slivers (fans, some CAD exports) should be
// remeshed, or this class extended to split slivers into strips before sampling.
//
// Speed. Triangles are binned once into a uniform grid of cubic cells (side >= the largest dent
// diameter given at construction), so a dent looks at <= 8 cells; each triangle it may touch is
// handled once (a per-triangle stamp), rows of samples inside the dent's disc are found in closed
// form. No allocation per dent. Memory: one bit per sample, plus ~130 bytes per triangle and
// 4 bytes per grid cell (see memory_bytes()).
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "common/vec.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

// Upper bound on the number of cells of the triangle grid; the cell side grows past the largest
// dent diameter when the part's bounding box would need more (4 bytes per cell).
inline constexpr std::int64_t kCoverageGridMaxCells = std::int64_t{1} << 21;

class CoverageMap {
public:
    // mesh: the component's surface (m, component frame); spacing_m: largest sample spacing h (m);
    // largest_dent_diameter_m: the largest dent expected (m); only sets the grid cell size, so a
    // larger dent is still handled correctly (it visits more cells).
    // Throws std::invalid_argument for a non-positive spacing or dent size.
    CoverageMap(const TriangleMesh& mesh, double spacing_m, double largest_dent_diameter_m);

    // The number of samples a map of `mesh` at `spacing_m` holds (to choose a spacing that fits
    // in memory before building it).
    static std::int64_t samples_needed(const TriangleMesh& mesh, double spacing_m);

    // Marks every sample within diameter_m / 2 (3D distance, m) of centre (m, component frame).
    void add_dent(const Vec3& centre, double diameter_m) {
        add_dent(centre, diameter_m, [](std::size_t, std::int64_t, std::uint64_t) {});
    }
    // The same, telling on_new(triangle, first, bits) of every sample it newly covers: bit k of
    // `bits` set for sample first + k (first a multiple of 64; bits only ever of that triangle).
    template <class OnNewlyCovered>
    void add_dent(const Vec3& centre, double diameter_m, OnNewlyCovered&& on_new) {
        visit_dent(
            centre, diameter_m, [this](std::size_t t) { return covered_count_[t] == samples_of_triangle(t); },  // fully covered already
            [&](std::size_t t, std::int64_t begin, std::int64_t count) {
                for (const std::int64_t end = begin + count; begin < end;) {
                    const std::int64_t word = begin >> 6, bit = begin & 63;
                    const std::int64_t n = std::min<std::int64_t>(64 - bit, end - begin);
                    const std::uint64_t mask = (n == 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << n) - 1)) << bit;
                    const std::uint64_t fresh = mask & ~covered_[static_cast<std::size_t>(word)];
                    if (fresh != 0) {
                        covered_[static_cast<std::size_t>(word)] |= fresh;
                        covered_count_[t] += std::popcount(fresh);
                        on_new(t, word << 6, fresh);
                    }
                    begin += n;
                }
            });
    }
    // Whether sample `index` (numbering of for_each_sample_row) is covered.
    bool covered(std::int64_t index) const { return (covered_[static_cast<std::size_t>(index >> 6)] >> (index & 63)) & 1u; }

    // The samples a dent of diameter_m centred at centre (m) covers, whether or not they are
    // covered already: calls visit(triangle, first, count) for each run of them (indices in the
    // numbering of for_each_sample_row), each triangle at most once per dent; skip(triangle) ->
    // true leaves a triangle out before its rows are searched. No allocation.
    template <class Skip, class Visit>
    void visit_dent(const Vec3& centre, double diameter_m, Skip&& skip, Visit&& visit) const {
        if (!(diameter_m > 0.0) || patches_.empty()) return;
        const double radius = 0.5 * diameter_m;  // m
        std::int64_t lo[3], hi[3];
        if (!dent_cells(centre, radius, lo, hi)) return;
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
            for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
                for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
                    const std::size_t c = static_cast<std::size_t>((z * dims_[1] + y) * dims_[0] + x);
                    for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
                        const std::uint32_t t = cell_triangles_[k];
                        if (stamp_[t] == dent_stamp_) continue;
                        stamp_[t] = dent_stamp_;
                        if (skip(static_cast<std::size_t>(t))) continue;
                        visit_patch(t, centre, radius, visit);
                    }
                }
    }
    // Forgets all dents.
    void clear();

    // Calls f(triangle, first (m), step (m), count, area (m^2), index) for every row of samples,
    // triangle by triangle: the row's samples lie at first + i step, i = 0 .. count - 1, each of
    // `area`; covered_samples(index, count) says how many of them a dent covers.
    template <class F>
    void for_each_sample_row(F&& f) const {
        for_each_sample_row(0, patches_.size(), f);
    }
    // The same for the triangles [first_triangle, end_triangle) only.
    template <class F>
    void for_each_sample_row(std::size_t first_triangle, std::size_t end_triangle, F&& f) const {
        for (std::size_t t = first_triangle; t < end_triangle; ++t) {
            const Patch& p = patches_[t];
            if (p.n == 0) continue;
            const std::int64_t n = p.n;
            const double area = p.area / static_cast<double>(n * n);
            for (int kind = 0; kind < 2; ++kind) {
                const double offset = kind == 0 ? 1.0 / 3.0 : 2.0 / 3.0;
                const std::int64_t last_row = kind == 0 ? n - 1 : n - 2;
                for (std::int64_t j = 0; j <= last_row; ++j) {
                    const std::int64_t row = p.first_sample + (kind == 0 ? up_row_offset(n, j) : down_row_offset(n, j));
                    const Vec3 first = p.origin + (static_cast<double>(j) + offset) * p.step_v + offset * p.step_u;
                    f(t, first, p.step_u, last_row - j + 1, area, row);
                }
            }
        }
    }
    // Calls f(index, point (m), u, v) for every sample of triangle t: (u, v) its coordinates along
    // the edges AB and AC (the point is A + u (B - A) + v (C - A)).
    template <class F>
    void for_each_sample_of_triangle(std::size_t t, F&& f) const {
        const Patch& p = patches_[t];
        const std::int64_t n = p.n;
        for (int kind = 0; kind < 2; ++kind) {
            const double offset = kind == 0 ? 1.0 / 3.0 : 2.0 / 3.0;
            const std::int64_t last_row = kind == 0 ? n - 1 : n - 2;
            for (std::int64_t j = 0; j <= last_row; ++j) {
                const std::int64_t row = p.first_sample + (kind == 0 ? up_row_offset(n, j) : down_row_offset(n, j));
                const double v = (static_cast<double>(j) + offset) / static_cast<double>(n);
                for (std::int64_t i = 0; i <= last_row - j; ++i) {
                    const double u = (static_cast<double>(i) + offset) / static_cast<double>(n);
                    f(row + i, p.origin + (static_cast<double>(i) + offset) * p.step_u + (static_cast<double>(j) + offset) * p.step_v, u,
                      v);
                }
            }
        }
    }
    std::int64_t first_sample_of_triangle(std::size_t t) const { return patches_[t].first_sample; }
    // m2, the area each sample of triangle t stands for
    double sample_area(std::size_t t) const {
        return patches_[t].n == 0 ? 0.0 : patches_[t].area / (static_cast<double>(patches_[t].n) * patches_[t].n);
    }

    // Covered samples among [index, index + count) of the numbering of for_each_sample_row.
    std::int64_t covered_samples(std::int64_t index, std::int64_t count) const;

    double coverage() const;                                                // covered area / total area, 0..1
    double coverage_of_triangle(std::size_t t) const;                       // 0..1; 0 for a degenerate triangle
    double coverage_of(const std::vector<int>& triangles) const;            // area-weighted over a region, 0..1
    double covered_area() const;                                            // m^2
    double total_area() const { return total_area_; }                       // m^2
    double triangle_area(std::size_t t) const { return patches_[t].area; }  // m^2

    std::size_t triangle_count() const { return patches_.size(); }
    std::int64_t sample_count() const { return sample_count_; }
    std::int64_t samples_of_triangle(std::size_t t) const;
    std::int64_t covered_samples_of_triangle(std::size_t t) const { return covered_count_[t]; }
    std::size_t memory_bytes() const;
    double spacing() const { return spacing_; }      // m, the bound h given at construction
    double grid_cell_size() const { return cell_; }  // m

private:
    // One triangle's sample grid (bits first_sample.. of covered_): sample (i, j) of the "up" sub-triangles sits at
    // origin + (i + 1/3) step_u + (j + 1/3) step_v (i + j <= n - 1); of the "down" ones at
    // origin + (i + 2/3) step_u + (j + 2/3) step_v (i + j <= n - 2).
    struct Patch {
        Vec3 origin;         // corner A (m)
        Vec3 step_u;         // (B - A) / n (m)
        Vec3 step_v;         // (C - A) / n (m)
        Vec3 unit_normal;    // (-)
        Vec3 centre;         // centre of the triangle's bounding sphere (m): the corners' box centre
        double reach = 0.0;  // radius of that sphere (m)
        double area = 0.0;   // m^2
        std::int64_t first_sample = 0;
        int n = 0;  // subdivisions per edge; 0 = degenerate triangle, no samples
    };

    // Offsets (in samples, from a triangle's first sample) of the rows of its sample grid. Rows are
    // stored in pairs, "up" row j (n - j samples) then "down" row j (n - 1 - j samples), so that a
    // dent, which marks neighbouring rows of both kinds, touches as few cache lines as possible.
    static std::int64_t up_row_offset(std::int64_t n, std::int64_t j) { return j * (2 * n - 1) - j * (j - 1); }
    static std::int64_t down_row_offset(std::int64_t n, std::int64_t j) { return up_row_offset(n, j) + n - j; }

    void build_grid(const TriangleMesh& mesh, double largest_dent_diameter_m);
    // The grid cells [lo, hi] a dent of radius_m at centre may touch (false: none), and a new
    // stamp for the triangles it visits.
    bool dent_cells(const Vec3& centre, double radius_m, std::int64_t lo[3], std::int64_t hi[3]) const;

    // The samples of triangle t within radius_m of centre, row by row. A sample at grid
    // coordinates (u, v) lies at in-plane offset u step_u + v step_v from the corner; inside the
    // dent iff G11 u^2 + 2 G12 u v + G22 v^2 - 2 b1 u - 2 b2 v + |w|^2 <= rho^2 (w: the centre
    // projected on the plane, rho: radius of the dent sphere's cut through the plane). Per row (v
    // fixed) that is an interval of u, found in closed form.
    template <class Visit>
    void visit_patch(std::size_t t, const Vec3& centre, double radius_m, Visit& visit) const {
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
                visit(t, row + static_cast<std::int64_t>(i_lo), static_cast<std::int64_t>(i_hi - i_lo) + 1);
            }
        }
    }

    double spacing_ = 0.0;     // m
    double total_area_ = 0.0;  // m^2
    std::vector<Patch> patches_;
    std::int64_t sample_count_ = 0;
    std::vector<std::uint64_t> covered_;        // one bit per sample: 1 = inside a dent
    std::vector<std::int64_t> covered_count_;   // per triangle: covered samples
    mutable std::vector<std::uint32_t> stamp_;  // per triangle: last dent that visited it
    mutable std::uint32_t dent_stamp_ = 0;

    // Triangle grid: cell (x, y, z) holds triangles cell_triangles_[cell_start_[c] .. cell_start_[c+1]).
    Vec3 grid_min_ = Vec3::Zero();  // m
    double cell_ = 0.0;             // m, cell side
    std::int64_t dims_[3] = {1, 1, 1};
    std::vector<std::uint32_t> cell_start_;
    std::vector<std::uint32_t> cell_triangles_;
};

}  // namespace peensim
