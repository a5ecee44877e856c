// The smoothed per-area fields (analysis/surface_smoothing.h): known patterns give known maps.
// Uniform impacts give a flat field equal to their density within the noise the class computes;
// one cluster gives the kernel's shape; a full coverage map smooths to 1; and the shipped gear at
// its 4960 triangles and a 60x finer tessellation of the same geometry give the same field at the
// same points; at_triangles() gives each triangle at()'s sums at its centroid, to the bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "analysis/coverage_map.h"
#include "analysis/surface_smoothing.h"
#include "geometry/box_mesh.h"
#include "geometry/spur_gear_mesh.h"
#include "kernels/closest_point.h"

using namespace peensim;

namespace {

Vec3 normal_of(const TriangleMesh& m, std::size_t t) {
    return (m.corner(t, 1) - m.corner(t, 0)).cross(m.corner(t, 2) - m.corner(t, 0)).normalized();
}
double area_of(const TriangleMesh& m, std::size_t t) {
    return 0.5 * (m.corner(t, 1) - m.corner(t, 0)).cross(m.corner(t, 2) - m.corner(t, 0)).norm();
}

// Points uniform over a mesh's area: a triangle picked by area, a point uniform in it.
class AreaSampler {
public:
    explicit AreaSampler(const TriangleMesh& mesh) : mesh_(mesh) {
        double sum = 0.0;
        for (std::size_t t = 0; t < mesh.triangle_count(); ++t) cumulative_.push_back(sum += area_of(mesh, t));
    }
    double area() const { return cumulative_.back(); }
    // The triangle and the point.
    std::pair<std::size_t, Vec3> draw(std::mt19937_64& rng) const {
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        const double at = unit(rng) * area();
        const auto t = static_cast<std::size_t>(std::upper_bound(cumulative_.begin(), cumulative_.end(), at) - cumulative_.begin());
        const std::size_t tri = std::min(t, mesh_.triangle_count() - 1);
        double u = unit(rng), v = unit(rng);
        if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
        const Vec3& a = mesh_.corner(tri, 0);
        return {tri, a + u * (mesh_.corner(tri, 1) - a) + v * (mesh_.corner(tri, 2) - a)};
    }

private:
    const TriangleMesh& mesh_;
    std::vector<double> cumulative_;  // m2
};

// A 40 x 40 x 2 mm plate, top face at z = 0, in 5 mm squares (two triangles each): triangles
// much larger than the radius, so a per-triangle field would be blocky.
TriangleMesh plate() {
    BoxSpec spec;
    spec.size_m = Vec3(0.04, 0.04, 0.002);
    spec.center_m = Vec3(0.0, 0.0, -0.001);
    spec.divisions = Eigen::Vector3i(8, 8, 1);
    return box(spec);
}

// The triangle of `mesh` nearest a point, found among the triangles whose boxes a grid of 1 mm
// cells lists around it (the coarse gear's triangle under a point of the fine one).
class NearestTriangle {
public:
    explicit NearestTriangle(const TriangleMesh& mesh) : mesh_(mesh) {
        lo_ = hi_ = mesh.vertices.front();
        for (const Vec3& v : mesh.vertices) lo_ = lo_.cwiseMin(v), hi_ = hi_.cwiseMax(v);
        lo_ -= Vec3::Constant(kCell);
        for (int k = 0; k < 3; ++k) dims_[k] = static_cast<int>((hi_[k] - lo_[k]) / kCell) + 2;
        cells_.resize(static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]));
        for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
            const Vec3 a = mesh.corner(t, 0).cwiseMin(mesh.corner(t, 1)).cwiseMin(mesh.corner(t, 2));
            const Vec3 b = mesh.corner(t, 0).cwiseMax(mesh.corner(t, 1)).cwiseMax(mesh.corner(t, 2));
            const auto i0 = index(a), i1 = index(b);
            for (int z = i0[2]; z <= i1[2]; ++z)
                for (int y = i0[1]; y <= i1[1]; ++y)
                    for (int x = i0[0]; x <= i1[0]; ++x) cells_[cell(x, y, z)].push_back(t);
        }
    }
    // (triangle, closest point); the point is assumed within a cell of the surface.
    std::pair<std::size_t, Vec3> operator()(const Vec3& p) const {
        const auto i = index(p);
        double best = 1e300;
        std::pair<std::size_t, Vec3> found{0, p};
        for (int z = std::max(i[2] - 1, 0); z <= std::min(i[2] + 1, dims_[2] - 1); ++z)
            for (int y = std::max(i[1] - 1, 0); y <= std::min(i[1] + 1, dims_[1] - 1); ++y)
                for (int x = std::max(i[0] - 1, 0); x <= std::min(i[0] + 1, dims_[0] - 1); ++x)
                    for (std::size_t t : cells_[cell(x, y, z)]) {
                        const Vec3 q = closest_point_on_triangle(p, mesh_.corner(t, 0), mesh_.corner(t, 1), mesh_.corner(t, 2)).point;
                        if ((q - p).squaredNorm() < best) best = (q - p).squaredNorm(), found = {t, q};
                    }
        return found;
    }

private:
    static constexpr double kCell = 1e-3;  // m
    std::array<int, 3> index(const Vec3& p) const {
        std::array<int, 3> i{};
        for (int k = 0; k < 3; ++k) i[static_cast<std::size_t>(k)] = std::clamp(static_cast<int>((p[k] - lo_[k]) / kCell), 0, dims_[k] - 1);
        return i;
    }
    std::size_t cell(int x, int y, int z) const { return static_cast<std::size_t>((z * dims_[1] + y) * dims_[0] + x); }
    const TriangleMesh& mesh_;
    Vec3 lo_, hi_;
    int dims_[3] = {1, 1, 1};
    std::vector<std::vector<std::size_t>> cells_;
};

}  // namespace

TEST(SurfaceSmoothing, UniformImpactsGiveAFlatFieldWithinTheComputedNoise) {
    const TriangleMesh mesh = plate();
    const double R = 1.5e-3;  // m
    SurfaceSmoothing smooth(mesh, R);
    const AreaSampler sampler(mesh);
    std::mt19937_64 rng(7);
    const int n = 400'000;
    for (int i = 0; i < n; ++i) {
        const auto [t, p] = sampler.draw(rng);
        smooth.add_impact(p, t, 2.0, 1e-3);
    }
    EXPECT_EQ(smooth.unplaced_impacts(), 0u);
    const double density = n / sampler.area();  // impacts per m2
    // The noise the class computes against the closed form of a flat surface, 1 / sqrt(lambda 5 pi R^2 / 9).
    const double expected_error = 1.0 / std::sqrt(density * 5.0 * std::numbers::pi * R * R / 9.0);
    // Probes on the top face 3.2 mm apart (independent: more than 2 R), also on its edges and
    // corners, where the kernel is cut by the facing factor: still flat.
    int probes = 0, within_2 = 0;
    double sum_z = 0.0, sum_z2 = 0.0, worst = 0.0;
    for (double x = -0.02; x <= 0.02 + 1e-12; x += 0.0032)
        for (double y = -0.02; y <= 0.02 + 1e-12; y += 0.0032) {
            const SmoothedSums s = smooth.at(Vec3(x, y, 0.0), Vec3::UnitZ());
            const double error = s.relative_error();
            ASSERT_TRUE(std::isfinite(error));
            if (std::abs(x) < 0.018 && std::abs(y) < 0.018) {
                EXPECT_NEAR(error, expected_error, 0.1 * expected_error) << x << " " << y;
            }
            const double z = (s.impacts_per_m2() - density) / (density * error);
            sum_z += z, sum_z2 += z * z, worst = std::max(worst, std::abs(z));
            within_2 += std::abs(z) < 2.0;
            ++probes;
        }
    // Standard normal deviates: mean 0 (+- 3 / sqrt(probes)), variance 1, 95 % within 2.
    EXPECT_LT(std::abs(sum_z / probes), 3.0 / std::sqrt(probes));
    EXPECT_NEAR(sum_z2 / probes, 1.0, 0.35);
    EXPECT_GT(within_2, static_cast<int>(0.88 * probes));
    EXPECT_LT(worst, 4.5);
    // Mean speed and energy per impact come back exactly as given.
    const SmoothedSums s = smooth.at(Vec3(0.001, 0.002, 0.0), Vec3::UnitZ());
    EXPECT_NEAR(s.mean_normal_speed(), 2.0, 1e-12);
    EXPECT_NEAR(s.energy_J_per_m2(), 1e-3 * s.impacts_per_m2(), 1e-9 * s.energy_J_per_m2());
}

TEST(SurfaceSmoothing, OneClusterGivesTheKernelsShape) {
    const TriangleMesh mesh = plate();
    const double R = 2e-3;  // m
    SurfaceSmoothing smooth(mesh, R);
    // 1000 impacts at one point of the top face (on a triangle's corner: any tessellation).
    const Vec3 centre(0.0, 0.0, 0.0);
    std::size_t top = 0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
        if (normal_of(mesh, t).z() > 0.9) top = t;
    for (int i = 0; i < 1000; ++i) smooth.add_impact(centre, top, 1.0, 0.0);
    // Density at distance d: N K(d) / integral of K over the plane, K = (1 - d^2/R^2)^2, integral pi R^2 / 3.
    const double peak = 1000.0 * 3.0 / (std::numbers::pi * R * R);
    for (double f : {0.0, 0.2, 0.4, 0.5, 0.6, 0.8, 0.95, 1.05, 1.5}) {
        for (const Vec3& direction : {Vec3(1, 0, 0), Vec3(0.6, 0.8, 0)}) {
            const Vec3 x = centre + f * R * direction;
            const double kernel = f < 1.0 ? (1 - f * f) * (1 - f * f) : 0.0;
            EXPECT_NEAR(smooth.at(x, Vec3::UnitZ()).impacts_per_m2(), peak * kernel, 0.02 * peak) << "at " << f << " R";
        }
    }
    // The plate's underside faces away: it sees none of them, 2 mm below.
    EXPECT_EQ(smooth.at(Vec3(0, 0, -0.002), -Vec3::UnitZ()).impacts, 0.0);
    EXPECT_TRUE(std::isnan(smooth.at(Vec3(0, 0, -0.002), -Vec3::UnitZ()).mean_normal_speed()));
}

TEST(SurfaceSmoothing, CoverageSmoothsToTheCoveredFraction) {
    const TriangleMesh mesh = plate();
    CoverageMap coverage(mesh, 0.05e-3, 1e-3);
    // Dents of 1 mm on a 1 mm grid over the top face: every point of it covered (the grid's
    // diagonal gaps closed by a second grid offset by half a step).
    for (double x = -0.0205; x <= 0.0205; x += 0.0005)
        for (double y = -0.0205; y <= 0.0205; y += 0.0005) coverage.add_dent(Vec3(x, y, 0.0), 1e-3);
    SurfaceSmoothing smooth(mesh, 1e-3);
    smooth.add_coverage(coverage);
    for (const Vec3& p : {Vec3(0, 0, 0), Vec3(0.0199, -0.0199, 0), Vec3(0.013, 0.004, 0)})
        EXPECT_NEAR(smooth.at(p, Vec3::UnitZ()).coverage(), 1.0, 1e-12) << p.transpose();
    // The underside: no dent reaches it (2 mm below), nothing covered.
    EXPECT_NEAR(smooth.at(Vec3(0.001, 0.003, -0.002), -Vec3::UnitZ()).coverage(), 0.0, 1e-12);
    // Half the top covered (x < 0): 1/2 on the line x = 0.
    coverage.clear();
    for (double x = -0.0205; x <= -0.0005 + 1e-12; x += 0.0005)
        for (double y = -0.0205; y <= 0.0205; y += 0.0005) coverage.add_dent(Vec3(x, y, 0.0), 1e-3 * (1.0 - 1e-9));
    SurfaceSmoothing half(mesh, 1e-3);
    half.add_coverage(coverage);
    EXPECT_NEAR(half.at(Vec3(0, 0.001, 0), Vec3::UnitZ()).coverage(), 0.5, 0.03);
    // A patch's samples count at its centroid, up to c (a quarter radius) from them: 1 and 0 from
    // 1.4 radii on.
    EXPECT_NEAR(half.at(Vec3(-0.0014, 0.001, 0), Vec3::UnitZ()).coverage(), 1.0, 1e-12);
    EXPECT_NEAR(half.at(Vec3(0.0014, 0.001, 0), Vec3::UnitZ()).coverage(), 0.0, 1e-12);
}

TEST(SurfaceSmoothing, TheGearAtTwoTessellationsGivesTheSameField) {
    const SpurGearSpec spec;  // the shipped gear: module 2 mm, 20 teeth, 10 mm wide, bore 5 mm, axis y
    const TriangleMesh coarse = spur_gear(spec, gear_resolution_for_triangle_count(spec, 5000));
    const TriangleMesh fine = spur_gear(spec, gear_resolution_for_triangle_count(spec, 300'000));
    ASSERT_EQ(coarse.triangle_count(), 4960u);
    ASSERT_GT(fine.triangle_count(), 250'000u);
    const double R = 1e-3;  // m
    SurfaceSmoothing on_coarse(coarse, R), on_fine(fine, R);
    // Dents of 0.4 mm at the first 20 000 impacts: coverage ~0.5 where they concentrate.
    CoverageMap coverage_coarse(coarse, 0.04e-3, 0.4e-3), coverage_fine(fine, 0.04e-3, 0.4e-3);
    // Impacts on the fine surface with a density that varies over a few mm: heavy on the teeth
    // facing -z (the sonotrode side), light above; each also given to the coarse gear at the
    // nearest point of its surface.
    const AreaSampler sampler(fine);
    const NearestTriangle nearest(coarse);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int placed = 0;
    while (placed < 300'000) {
        const auto [t, p] = sampler.draw(rng);
        const double weight = 0.1 + 0.9 * std::exp(-(p.z() + 0.022) / 0.008) * (0.6 + 0.4 * std::cos(p.x() / 0.003));
        if (unit(rng) > std::min(weight, 1.0)) continue;
        on_fine.add_impact(p, t, 1.0 + p.z() * 10.0 + 0.5, 1e-6);
        const auto [tc, q] = nearest(p);
        on_coarse.add_impact(q, tc, 1.0 + p.z() * 10.0 + 0.5, 1e-6);
        if (placed < 20'000) {
            coverage_fine.add_dent(p, 0.4e-3);
            coverage_coarse.add_dent(q, 0.4e-3);
        }
        ++placed;
    }
    std::printf("  patches: %zu (4960 triangles), %zu (%zu triangles); memory %.1f MB, %.1f MB\n", on_coarse.patch_count(),
                on_fine.patch_count(), fine.triangle_count(), on_coarse.memory_bytes() / 1e6, on_fine.memory_bytes() / 1e6);
    EXPECT_EQ(on_fine.unplaced_impacts(), 0u);
    EXPECT_EQ(on_coarse.unplaced_impacts(), 0u);
    on_fine.add_coverage(coverage_fine);
    on_coarse.add_coverage(coverage_coarse);
    // Probes: every 97th triangle of the fine gear, at its centroid; for the coarse one the
    // nearest point of its surface with the normal of the triangle there.
    double worst = 0.0, sum2 = 0.0, worst_speed = 0.0, max_density = 0.0, worst_coverage = 0.0, sum2_coverage = 0.0;
    int probes = 0;
    std::vector<std::pair<double, double>> pairs;
    for (std::size_t t = 0; t < fine.triangle_count(); t += 97) {
        const Vec3 p = (fine.corner(t, 0) + fine.corner(t, 1) + fine.corner(t, 2)) / 3.0;
        const auto [tc, q] = nearest(p);
        const SmoothedSums a = on_fine.at(p, normal_of(fine, t));
        const SmoothedSums b = on_coarse.at(q, normal_of(coarse, tc));
        pairs.emplace_back(a.impacts_per_m2(), b.impacts_per_m2());
        max_density = std::max(max_density, a.impacts_per_m2());
        const double dc = std::abs(a.coverage() - b.coverage());
        worst_coverage = std::max(worst_coverage, dc);
        sum2_coverage += dc * dc;
        if (a.impacts > 50.0) worst_speed = std::max(worst_speed, std::abs(a.mean_normal_speed() - b.mean_normal_speed()));
        ++probes;
    }
    for (const auto& [a, b] : pairs) {
        const double d = std::abs(a - b) / max_density;
        worst = std::max(worst, d);
        sum2 += d * d;
    }
    const double rms = std::sqrt(sum2 / probes);
    const double rms_coverage = std::sqrt(sum2_coverage / probes);
    std::printf(
        "  gear, 4960 vs %zu triangles, R = 1 mm, %d probes: density differs by %.2f %% rms, %.2f %% at worst (of the "
        "largest); mean speed by %.4f m/s at worst; coverage by %.4f rms, %.4f at worst\n",
        fine.triangle_count(), probes, 100.0 * rms, 100.0 * worst, worst_speed, rms_coverage, worst_coverage);
    EXPECT_LT(rms, 0.01);
    EXPECT_LT(worst, 0.05);
    EXPECT_LT(worst_speed, 0.01);
    EXPECT_LT(rms_coverage, 0.005);
    EXPECT_LT(worst_coverage, 0.03);

    // at_triangles() takes a fine mesh's triangles cube by cube over copies of the patches near
    // each cube (the coarse one's mostly one by one): each triangle's sums are at()'s at its
    // centroid, to the bit.
    for (const auto* pair : {&fine, &coarse}) {
        const TriangleMesh& mesh = *pair;
        const SurfaceSmoothing& smoothing = pair == &fine ? on_fine : on_coarse;
        const std::vector<SmoothedSums> all = smoothing.at_triangles();
        ASSERT_EQ(all.size(), mesh.triangle_count());
        std::size_t differ = 0;
        for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
            const SmoothedSums one = smoothing.at((mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0, normal_of(mesh, t));
            const SmoothedSums& a = all[t];
            differ += a.area_m2 != one.area_m2 || a.impacts != one.impacts || a.impacts_sq != one.impacts_sq ||
                              a.energy_J != one.energy_J || a.vn_sum_m_per_s != one.vn_sum_m_per_s || a.covered_m2 != one.covered_m2 ||
                              a.sampled_m2 != one.sampled_m2
                          ? 1
                          : 0;
        }
        EXPECT_EQ(differ, 0u) << mesh.triangle_count() << " triangles";
    }
}

TEST(SurfaceSmoothing, MemoryIsBoundedByTheSurfaceNotTheImpacts) {
    const TriangleMesh mesh = plate();
    SurfaceSmoothing smooth(mesh, 1e-3);
    const std::size_t before = smooth.memory_bytes();
    const AreaSampler sampler(mesh);
    std::mt19937_64 rng(3);
    for (int i = 0; i < 200'000; ++i) {
        const auto [t, p] = sampler.draw(rng);
        smooth.add_impact(p, t, 1.0, 0.0);
    }
    EXPECT_EQ(smooth.memory_bytes(), before);
    // ~1.5 patches per c^2 of area (c = R / 4), 120 bytes each plus the key table.
    const double area = sampler.area();
    const double c = 1e-3 / kSmoothingCellsPerRadius;
    EXPECT_LT(static_cast<double>(smooth.patch_count()), 2.0 * area / (c * c));
    EXPECT_GT(static_cast<double>(smooth.patch_count()), 0.9 * area / (c * c));
    EXPECT_THROW(SurfaceSmoothing(mesh, 0.0), std::invalid_argument);
}
