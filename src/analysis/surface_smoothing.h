// Per-area fields of one component smoothed over a radius R of its surface: the maps of
// `render-impacts` and the `*_smoothed` columns of the analysis, the same whatever the mesh's
// tessellation. Pure computation: no file I/O.
//
// Why. A per-triangle field (impacts per mm2 of each triangle) shows the mesh, not the process:
// on a fine mesh most triangles hold one impact or none (speckle), on a coarse one a big triangle
// averages away what happens across it. Here the surface area and the impacts are binned by
// position, finely and without regard to the triangles, and the field at a point x of the surface
// (unit normal n) is the ratio of the two, smoothed by one kernel:
//
//   impacts per m2 (x) = sum_i w(x, x_i) / sum_p w(x, x_p) A_p      (impacts i, surface patches p)
//   w(x, y) = (1 - |x - y|^2 / R^2)^2 max(0, n . n_y)   for |x - y| < R, else 0
//
// the quartic (biweight) kernel of support R, times a facing factor: a point sees only the
// surface that faces its way, so the two flanks of a thin tooth or the faces either side of a
// sharp edge are not averaged together. Numerator and denominator share the kernel, so a uniform
// density of impacts gives a flat field everywhere, next to an edge or on a curved face too.
// Energy per area, covered fraction and mean normal speed are ratios of the same kind.
//
// Binning. Space is cut into cubes of side c = R / kSmoothingCellsPerRadius (coarser only when the
// surface would need more than kMaxSmoothingPatches); a patch is the surface in one cube facing one
// of the 6 axis directions (the largest component of its triangles' normal, with its sign), so
// opposite faces of a thin wall never share a patch. A patch keeps its area (from sub-triangles of
// edge <= c/2, each counted at its centroid), that area's centroid and mean normal; the number,
// centroid, summed energy and normal speed of its impacts; and the covered and sampled area of the
// coverage map's samples. Memory: 120 bytes per patch and 32-64 bytes of key table, ~1.2 A / c^2
// patches for area A: bounded by the surface, whatever the number of impacts or triangles (the
// shipped gear at R = 1 mm: 99k patches, 17 MB with its 4960 triangles, 24 MB with 300k).
//
// Accuracy. A patch's contents are counted at their centroid; for the smooth kernel the error
// that makes is second order in c / R (within 2 % of the peak at c = R/4, measured in the tests). Noise: for impacts
// at random (Poisson), the relative standard error of the smoothed density at x is
// sqrt(sum_i w_i^2) / sum_i w_i (SmoothedSums::relative_error); for a uniform density lambda on a
// flat surface, 1 / sqrt(lambda 5 pi R^2 / 9): the kernel holds the information of the impacts on
// 5/9 of its disc.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "common/vec.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

class CoverageMap;

inline constexpr double kSmoothingCellsPerRadius = 4.0;       // bin side c = R / this
inline constexpr std::size_t kMaxSmoothingPatches = 300'000;  // patches per component at most (~50 MB with the key table)
inline constexpr double kSmoothingSamplesPerCell = 2.0;       // area samples: sub-triangle edge <= c / this

// Kernel-weighted sums at one point of the surface (weights w as above, dimensionless).
struct SmoothedSums {
    double area_m2 = 0.0;         // m2, sum_p w A_p
    double impacts = 0.0;         // sum_i w
    double impacts_sq = 0.0;      // sum_i w^2 (the Poisson variance of `impacts`)
    double energy_J = 0.0;        // J, sum_i w E_i (E = 1/2 m vn^2)
    double vn_sum_m_per_s = 0.0;  // m/s, sum_i w vn_i
    double covered_m2 = 0.0;      // m2, sum w (covered area of the coverage samples)
    double sampled_m2 = 0.0;      // m2, sum w (area of the coverage samples)

    // Impacts per m2 (NaN where no surface is within R: a degenerate point).
    double impacts_per_m2() const { return area_m2 > 0.0 ? impacts / area_m2 : std::numeric_limits<double>::quiet_NaN(); }
    // J/m2, normal impact energy delivered per area.
    double energy_J_per_m2() const { return area_m2 > 0.0 ? energy_J / area_m2 : std::numeric_limits<double>::quiet_NaN(); }
    // m/s, impact-weighted mean normal speed (NaN without an impact within R).
    double mean_normal_speed() const { return impacts > 0.0 ? vn_sum_m_per_s / impacts : std::numeric_limits<double>::quiet_NaN(); }
    // Covered fraction, 0..1 (NaN without coverage samples within R: no coverage map).
    double coverage() const { return sampled_m2 > 0.0 ? covered_m2 / sampled_m2 : std::numeric_limits<double>::quiet_NaN(); }
    // Relative standard error of impacts_per_m2 for impacts at random (NaN without an impact).
    double relative_error() const { return impacts > 0.0 ? std::sqrt(impacts_sq) / impacts : std::numeric_limits<double>::quiet_NaN(); }
};

class SurfaceSmoothing {
public:
    // mesh: the component's surface (m, component frame; it must outlive this); radius_m: the
    // kernel's support R (m). Throws std::invalid_argument for a radius that is not positive and finite.
    SurfaceSmoothing(const TriangleMesh& mesh, double radius_m);

    // One impact at point_m (component frame) on triangle `triangle` of the mesh (its normal picks
    // the patch facing), normal speed vn (m/s), normal kinetic energy (J). Allocates nothing.
    void add_impact(const Vec3& point_m, std::size_t triangle, double vn_m_per_s, double energy_J);

    // The samples of a coverage map of the same mesh (covered or not): once, after the impacts.
    void add_coverage(const CoverageMap& coverage);

    // Kernel sums at a point of the surface with unit normal n (m, component frame).
    SmoothedSums at(const Vec3& point_m, const Vec3& unit_normal) const;
    // at() at every triangle's centroid, with its normal (zero sums for a degenerate triangle).
    std::vector<SmoothedSums> at_triangles() const;

    double radius_m() const { return radius_; }  // m, R
    double cell_m() const { return cell_; }      // m, c
    std::size_t patch_count() const { return area_.size(); }
    std::size_t memory_bytes() const;
    // Impacts no patch was found for (a point off the mesh, or a degenerate triangle).
    std::uint64_t unplaced_impacts() const { return unplaced_; }

private:
    std::uint64_t key_of(const Vec3& p, int facing) const;
    // Index of the patch for a point on a surface of this facing (-1: none near).
    std::int64_t patch_for(const Vec3& p, const Vec3& unit_normal, int facing) const;
    std::int64_t find(std::uint64_t key) const;
    std::uint32_t insert(std::uint64_t key);
    void build_neighbour_grid();
    // Calls visit(patch) for every patch in the neighbour grid's cube holding p and the 26 around
    // it (none for a point more than a cube outside the grid).
    template <typename Visit>
    void for_each_patch_near(const Vec3& p, Visit&& visit) const;

    const TriangleMesh* mesh_;
    double radius_ = 0.0;                // m
    double cell_ = 0.0;                  // m, bin side
    double inverse_cell_ = 0.0;          // 1/m
    Vec3 origin_ = Vec3::Zero();         // m, corner of bin (0, 0, 0)
    std::vector<Vec3> triangle_normal_;  // unit (zero for a degenerate triangle)
    std::vector<std::int8_t> triangle_facing_;

    // Patches (structure of arrays).
    std::vector<Vec3> centroid_;  // m: area centroid
    std::vector<Vec3> normal_;    // unit: area-weighted mean normal
    std::vector<double> area_;    // m2
    // What a patch's impacts add up to, together: one cache line touched per impact.
    struct ImpactSums {
        double count = 0.0;
        Vec3 point_sum = Vec3::Zero();  // m: summed impact points (their centroid once divided)
        double energy_J = 0.0;          // J
        double vn_sum = 0.0;            // m/s
    };
    std::vector<ImpactSums> impacts_;
    std::vector<double> covered_;  // m2
    std::vector<double> sampled_;  // m2

    // Bin key -> patch: open addressing, linear probing, key + 1 (0 = empty slot).
    struct Slot {
        std::uint64_t key_plus_one = 0;
        std::uint32_t patch = 0;
    };
    std::vector<Slot> slots_;

    // Neighbour grid over patch centroids: cubes of side >= R + the farthest an impact centroid
    // lies from its patch's area centroid; patches of cube g are grid_patch_[grid_start_[g] ..).
    Vec3 grid_min_ = Vec3::Zero();
    double grid_cell_ = 0.0;  // m
    std::int64_t grid_dims_[3] = {1, 1, 1};
    std::vector<std::uint32_t> grid_start_;
    std::vector<std::uint32_t> grid_patch_;

    std::uint64_t unplaced_ = 0;
};

}  // namespace peensim
