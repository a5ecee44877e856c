// CoverageMap against closed forms: one dent, a lattice of dents, random (Poisson) dents with the
// reference's exact relation C = 1 - exp(-A_r), shared edges, and a timing print.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "analysis/coverage_map.h"
#include "geometry/box_mesh.h"
#include "geometry/cylinder_mesh.h"
#include "support/test_meshes.h"

namespace peensim {
namespace {

using peensim::testing::square;

TEST(AnalysisCoverage, SamplesCarryTheTrianglesAreaAndRespectTheSpacing) {
    const double side = 4e-3, h = 0.2e-3;  // m
    const CoverageMap map(square(side), h, 1e-3);
    const int n = static_cast<int>(std::ceil(side * std::sqrt(2.0) / h));  // the diagonal is longest
    EXPECT_EQ(map.samples_of_triangle(0), static_cast<std::int64_t>(n) * n);
    EXPECT_EQ(map.sample_count(), 2 * static_cast<std::int64_t>(n) * n);
    EXPECT_LE(side * std::sqrt(2.0) / n, h);
    EXPECT_NEAR(map.total_area(), side * side, 1e-18);
    EXPECT_EQ(map.coverage(), 0.0);
}

// Relative error of the area of one dent of diameter d centred near the middle of the square, at
// spacing h; the header's bound is 8 h / d. Returns {max, rms} over 16 centres.
std::pair<double, double> single_dent_errors(double h) {
    const double side = 4e-3, d = 1e-3;  // m
    CoverageMap map(square(side), h, d);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> jitter(-0.1e-3, 0.1e-3);
    const double exact = M_PI * d * d / 4.0;  // m^2
    double max_error = 0.0, sum_sq = 0.0;
    for (int k = 0; k < 16; ++k) {
        map.clear();
        map.add_dent(Vec3(2e-3 + jitter(rng), 2e-3 + jitter(rng), 0.0), d);
        const double error = std::abs(map.covered_area() - exact) / exact;
        max_error = std::max(max_error, error);
        sum_sq += error * error;
    }
    return {max_error, std::sqrt(sum_sq / 16.0)};
}

TEST(AnalysisCoverage, SingleDentAreaWithinTheSamplingBound) {
    const double d = 1e-3;  // m
    const auto [coarse_max, coarse_rms] = single_dent_errors(d / 5.0);
    const auto [fine_max, fine_rms] = single_dent_errors(d / 20.0);
    std::printf("[ coverage ] one dent, h = d/5:  max %.4f rms %.4f (bound %.2f)\n", coarse_max, coarse_rms, 8.0 / 5.0);
    std::printf("[ coverage ] one dent, h = d/20: max %.4f rms %.4f (bound %.2f)\n", fine_max, fine_rms, 8.0 / 20.0);
    EXPECT_LE(coarse_max, 8.0 / 5.0);
    EXPECT_LE(fine_max, 8.0 / 20.0);
    EXPECT_LT(fine_rms, coarse_rms);  // the error shrinks with the spacing
    EXPECT_LT(fine_max, 0.02);        // measured: well inside the worst-case bound
}

TEST(AnalysisCoverage, LatticeOfSeparateDents) {
    const double side = 10e-3, d = 1e-3, pitch = 1.5e-3, h = d / 20.0;  // m
    CoverageMap map(square(side), h, d);
    int count = 0;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j, ++count) map.add_dent(Vec3(0.75e-3 + pitch * i, 0.8e-3 + pitch * j, 0.0), d);
    const double exact = count * M_PI * d * d / 4.0 / (side * side);
    const double bound = 2.0 * h * count * M_PI * d / (side * side);
    std::printf("[ coverage ] lattice of %d dents: %.5f vs %.5f (error %.2e, bound %.2e)\n", count, map.coverage(), exact,
                std::abs(map.coverage() - exact), bound);
    EXPECT_NEAR(map.coverage(), exact, bound);
    EXPECT_NEAR(map.coverage(), exact, 0.01 * exact);
}

TEST(AnalysisCoverage, DentOnASharedEdgeCoversBothTriangles) {
    const double side = 4e-3, d = 1e-3;  // m
    CoverageMap map(square(side), d / 20.0, d);
    map.add_dent(Vec3(2e-3, 2e-3, 0.0), d);  // on the diagonal both triangles share
    EXPECT_GT(map.covered_samples_of_triangle(0), 0);
    EXPECT_GT(map.covered_samples_of_triangle(1), 0);
    // By symmetry each triangle holds half the dent.
    const double half = M_PI * d * d / 8.0 / (side * side / 2.0);
    EXPECT_NEAR(map.coverage_of_triangle(0), half, 0.02 * half);
    EXPECT_NEAR(map.coverage_of_triangle(1), half, 0.02 * half);
    EXPECT_NEAR(map.coverage_of({0, 1}), map.coverage(), 1e-15);
    // A dent lifted off the plane by more than its radius touches nothing.
    map.clear();
    map.add_dent(Vec3(2e-3, 2e-3, 0.51e-3), d);
    EXPECT_EQ(map.coverage(), 0.0);
}

// Standard deviation of the covered fraction of area S in a Boolean model of discs of radius r at
// density lambda (1/m^2): Var = (1/S) int q^2 (exp(lambda K(s)) - 1) 2 pi s ds, q = exp(-lambda pi r^2),
// K(s) the area shared by two discs whose centres are s apart (valid for S >> r^2).
double boolean_model_sigma(double lambda, double r, double area) {
    const double q = std::exp(-lambda * M_PI * r * r);
    const int steps = 4000;
    double integral = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double s = (i + 0.5) * 2.0 * r / steps;
        const double lens = 2.0 * r * r * std::acos(s / (2.0 * r)) - 0.5 * s * std::sqrt(4.0 * r * r - s * s);
        integral += q * q * std::expm1(lambda * lens) * 2.0 * M_PI * s * (2.0 * r / steps);
    }
    return std::sqrt(integral / area);
}

TEST(AnalysisCoverage, RandomDentsFollowTheExactAvramiRelation) {
    // Centres uniform over the square grown by a radius on each side, Poisson count: every point of
    // the square is then covered with probability exactly 1 - exp(-A_r), A_r = lambda pi d^2 / 4.
    const double side = 40e-3, d = 1e-3, r = d / 2.0, h = d / 8.0;  // m
    const double grown_area = (side + d) * (side + d);              // m^2
    CoverageMap map(square(side), h, d);
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<double> position(-r, side + r);
    for (double area_ratio : {0.5, 1.0, 2.0, std::log(50.0)}) {
        map.clear();
        const double lambda = area_ratio / (M_PI * r * r);  // dents per m^2
        std::poisson_distribution<long> count(lambda * grown_area);
        const long dents = count(rng);
        for (long k = 0; k < dents; ++k) map.add_dent(Vec3(position(rng), position(rng), 0.0), d);
        const double expected = -std::expm1(-area_ratio);
        const double sigma = boolean_model_sigma(lambda, r, side * side);
        // Sampling adds no bias for random dents (see coverage_map.h); its scatter, ~sqrt(dents)
        // per-dent errors of ~1 % of a dent's area (h = d/8), is ~5e-4 here: allow 1e-3.
        const double tolerance = 4.0 * sigma + 1e-3;
        std::printf("[ coverage ] A_r = %.2f: %.5f vs %.5f (diff %+.5f, sigma %.5f, %ld dents)\n", area_ratio, map.coverage(), expected,
                    map.coverage() - expected, sigma, dents);
        EXPECT_NEAR(map.coverage(), expected, tolerance) << "A_r = " << area_ratio;
    }
}

TEST(AnalysisCoverage, TimingOfAMillionDentsOnAMillionSamples) {
    const double side = 10e-3;                       // m
    const double h = side * std::sqrt(2.0) / 707.0;  // m: 707 per edge, 2 * 707^2 samples
    const double d = 0.2e-3;                         // m: a dent of a 1 mm shot at ~40 m/s
    CoverageMap map(square(side), h, d);
    EXPECT_NEAR(static_cast<double>(map.sample_count()), 1.0e6, 1.0e3);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> position(0.0, side);
    std::vector<Vec3> centres(1000000);
    for (Vec3& c : centres) c = Vec3(position(rng), position(rng), 0.0);
    const auto start = std::chrono::steady_clock::now();
    for (const Vec3& c : centres) map.add_dent(c, d);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf(
        "[ coverage ] 1e6 dents (d = %.0f um, ~%.0f samples each) on %lld samples: %.3f s, %.0f ns/dent, "
        "coverage %.4f, memory %.1f MB\n",
        d * 1e6, M_PI * d * d / 4.0 / (side * side) * 1e6, static_cast<long long>(map.sample_count()), seconds, seconds * 1e3,
        map.coverage(), map.memory_bytes() / 1e6);
    EXPECT_GT(map.coverage(), 0.999);  // A_r = 1e6 * pi (0.1 mm)^2 / 100 mm^2 = 314: saturated
}

TEST(AnalysisCoverage, TimingOnAManyTriangleCylinder) {
    // A rod of radius 10 mm, 20 mm long (~1900 mm^2 with its caps, the order of a gear's surface):
    // 20k wall triangles, where the triangle grid matters.
    CylinderSpec spec;
    spec.radius_m = 10e-3;
    spec.height_m = 20e-3;
    spec.segments = 256;
    spec.axial_subdivisions = 40;
    spec.cap_rings = 20;      // no 10 mm-long fan slivers: see "Slender triangles" in coverage_map.h
    const double d = 0.1e-3;  // m: the gear case's 20 um spacing, dents of ~20 samples across
    const TriangleMesh mesh = cylinder(spec);
    std::vector<int> wall;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
        if (mesh.group_names[static_cast<std::size_t>(mesh.group_of_triangle[t])] == "wall") wall.push_back(static_cast<int>(t));
    CoverageMap map(mesh, 0.02e-3, d);
    std::mt19937_64 rng(6);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI), height(-10e-3, 10e-3);
    std::vector<Vec3> centres(1000000);
    for (Vec3& c : centres) {
        const double a = angle(rng);
        c = Vec3(10e-3 * std::cos(a), 10e-3 * std::sin(a), height(rng));
    }
    const auto start = std::chrono::steady_clock::now();
    for (const Vec3& c : centres) map.add_dent(c, d);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    double wall_area = 0.0;  // m^2
    for (int t : wall) wall_area += map.triangle_area(static_cast<std::size_t>(t));
    const double area_ratio = 1e6 * M_PI * d * d / 4.0 / wall_area;
    std::printf(
        "[ coverage ] cylinder, %zu triangles, %lld samples: 1e6 dents in %.3f s, %.0f ns/dent, "
        "memory %.1f MB, wall coverage %.4f (A_r %.3f -> %.4f)\n",
        map.triangle_count(), static_cast<long long>(map.sample_count()), seconds, seconds * 1e3, map.memory_bytes() / 1e6,
        map.coverage_of(wall), area_ratio, -std::expm1(-area_ratio));
    // Dents are centred on the wall: its coverage follows the exact relation (wall edges aside).
    EXPECT_NEAR(map.coverage_of(wall), -std::expm1(-area_ratio), 0.01);
}

}  // namespace
}  // namespace peensim

// A face lying exactly on a boundary of the coverage map's dent grid must still be found: a unit
// cube with 0.1 m grid cells puts its faces on cell boundaries.
TEST(AnalysisCoverage, FacesOnGridCellBoundariesAreCovered) {
    peensim::BoxSpec spec;
    spec.size_m = peensim::Vec3(1.0, 1.0, 1.0);
    spec.center_m = peensim::Vec3(0.5, 0.5, 0.5);
    const peensim::TriangleMesh cube = peensim::box(spec);
    peensim::CoverageMap map(cube, 0.01, 0.1);
    map.add_dent(peensim::Vec3(0.5, 0.5, 1.0), 0.1);         // the middle of the top face (z = 1)
    map.add_dent(peensim::Vec3(0.5, 0.0, 0.5), 0.1);         // the middle of the y = 0 face
    const double expected = 2.0 * M_PI * 0.05 * 0.05 / 6.0;  // two discs on a 6 m2 surface
    EXPECT_NEAR(map.coverage(), expected, 0.1 * expected);
}
