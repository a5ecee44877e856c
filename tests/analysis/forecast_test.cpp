// Coverage per sample (reach, regions), coverage as dents land, and the forecast of the time to a
// coverage target against exact answers: dents at random on a closed surface at known rates.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <set>
#include <vector>

#include "analysis/coverage_forecast.h"
#include "analysis/coverage_progress.h"
#include "analysis/reach_boundary.h"
#include "analysis/regions.h"
#include "analysis/sample_classes.h"
#include "common/parallel_chunks.h"
#include "common/random.h"
#include "geometry/box_mesh.h"
#include "geometry/mesh_checks.h"

namespace peensim {
namespace {

constexpr double kTarget = 0.98;

RegionDesc half_space_region(const std::string& name, const Vec3& normal) {
    RegionDesc r;
    r.name = name;
    r.half_space = HalfSpaceCondition{Vec3::Zero(), normal};
    return r;
}

const ReachTest kEverywhere = [](const Vec3&, std::size_t, double) { return true; };

std::unique_ptr<CoverageProgress> progress_of(const TriangleMesh& mesh, const RegionSet& regions, const ReachTest& reach, double spacing,
                                              double dent) {
    auto map = std::make_unique<CoverageMap>(mesh, spacing, dent);
    SampleClasses classes(*map, mesh, regions, reach, 1.0, 10.0 * spacing);
    return std::make_unique<CoverageProgress>(std::move(map), std::move(classes), kTarget);
}

TEST(SampleClasses, ATriangleIsPartlyReachableAtTheSamplesResolution) {
    // One square of 2 triangles, 1 m; a shot reaches x < 0.3 only: the boundary cuts both triangles.
    const TriangleMesh plate = box(BoxSpec{Vec3(1, 1, 1), Vec3(0.5, 0.5, -0.5), Eigen::Vector3i(1, 1, 1)});
    const RegionSet none(plate, {});
    const ReachTest left = [](const Vec3& p, std::size_t, double) { return p.x() < 0.3; };
    const double spacing = 0.01;  // m
    CoverageMap map(plate, spacing, 0.05);
    const SampleClasses classes(map, plate, none, left, 1.0, 0.1);
    // The 6 faces: the top (z = 0) and bottom have 0.3 m2 each in reach, x = 0 face wholly, x = 1 not,
    // the y faces 0.3 each: 0.3 * 4 + 1 = 2.2 m2, to the samples' resolution (a row of them).
    EXPECT_NEAR(classes.reachable_area_m2(), 2.2, 2 * spacing);
    EXPECT_NEAR(classes.peened_area_m2(), classes.reachable_area_m2(), 1e-12);
    // Only the triangles the boundary crosses were tested sample by sample.
    int mixed = 0;
    for (std::size_t t = 0; t < plate.triangle_count(); ++t) mixed += classes.triangle_class(t) == SampleClasses::kMixed;
    EXPECT_EQ(mixed, 8);  // 2 per face crossed by x = 0.3: top, bottom, y = 0, y = 1
    EXPECT_LT(classes.sample_tests(), map.sample_count() / 4);
    // Every sample agrees with the test at its own position.
    for (std::size_t t = 0; t < plate.triangle_count(); ++t)
        map.for_each_sample_of_triangle(t, [&](std::int64_t index, const Vec3& p, double, double) {
            EXPECT_EQ(classes.info(classes.class_of(t, index)).reachable, p.x() < 0.3) << p.transpose();
        });
}

TEST(SampleClasses, RegionsAndExclusionPerSample) {
    // Unit cube at the origin: an excluded region x > 0.25 (crossing triangles), a region z > 0.
    const TriangleMesh cube = box(BoxSpec{Vec3::Ones(), Vec3::Zero(), Eigen::Vector3i(2, 2, 2)});
    RegionDesc masked = half_space_region("masked", Vec3::UnitX());
    masked.half_space->point_m = Vec3(0.25, 0, 0);
    masked.exclude = true;
    const RegionSet regions(cube, {masked, half_space_region("top", Vec3::UnitZ())});
    auto p = progress_of(cube, regions, kEverywhere, 0.01, 0.05);
    const SampleClasses& c = p->classes();
    // Peened: x < 0.25 of the 6 m2: faces y, z (4 of them) 0.75 each, the x = -0.5 face 1.
    EXPECT_NEAR(c.peened_area_m2(), 4 * 0.75 + 1.0, 0.02);
    EXPECT_NEAR(c.region_peened_area_m2(1), 0.75 + 2 * 0.5 * 0.75 + 0.5, 0.02);  // top half: +z face and half of 3 sides
    EXPECT_NEAR(c.region_peened_area_m2(0), 0.0, 1e-12);                         // excluded: never peened
    EXPECT_NEAR(c.region_counted_area_m2(0), 4 * 0.25 + 1.0, 0.02);              // its coverage, for information, over it all
}

TEST(CoverageProgress, CoverageOfAreasAndWhenTheyReachTheTarget) {
    const TriangleMesh cube = box(BoxSpec{Vec3::Ones(), Vec3::Zero(), Eigen::Vector3i(1, 1, 1)});
    RegionDesc top;
    top.name = "top";
    top.facing = FacingCondition{Vec3::UnitZ(), 1e-3};
    const RegionSet regions(cube, {top});
    auto p = progress_of(cube, regions, kEverywhere, 0.01, 0.5);
    EXPECT_EQ(p->coverage(), 0.0);
    EXPECT_TRUE(std::isnan(p->region_reached_at_s(0)));
    // Dents of 0.5 m on the top face's grid: the face is covered once the last lands.
    double t = 0.0;
    for (double x = -0.45; x < 0.5; x += 0.15)
        for (double y = -0.45; y < 0.5; y += 0.15) p->add_dent(Vec3(x, y, 0.5), 0.5, t += 1.0);
    EXPECT_NEAR(p->region_coverage(0), 1.0, 1e-12);
    const double reached = p->region_reached_at_s(0);
    ASSERT_FALSE(std::isnan(reached));
    EXPECT_LE(reached, t);
    EXPECT_TRUE(std::isnan(p->reached_at_s()));  // the whole cube is not
    EXPECT_NEAR(p->coverage(), p->map().covered_area() / 6.0, 1e-12);
}

// Dents at random on the faces of a closed cube (side `side`): face f gets impacts at rate rate[f]
// (1/(m2 s)) for `window` s, dents of area `dent_area`, impacts in equal time batches.
struct Peening {
    TriangleMesh cube;
    std::vector<double> rate;  // per face (-x, +x, -y, +y, -z, +z): 1/(m2 s)
    double dent_area = 0.0;    // m2
    double side = 0.0;         // m
    // The share of the face's rate at a point (1: all of it), a pattern of the part's own below h.
    std::function<double(const Vec3&)> share = [](const Vec3&) { return 1.0; };
};

// The exact time to the target of the whole cube (or of face `only`) from t = 0: sum_f A_f exp(-mu_f t)
// = (1 - target) sum_f A_f, mu_f = rate_f dent_area (dents covering a point at random, per s).
double exact_time(const Peening& p, int only = -1) {
    const auto uncovered = [&](double t) {
        double u = 0.0, area = 0.0;
        for (int f = 0; f < 6; ++f) {
            if (only >= 0 && f != only) continue;
            u += std::exp(-p.rate[static_cast<std::size_t>(f)] * p.dent_area * t);
            area += 1.0;
        }
        return u / area;
    };
    double lo = 0.0, hi = 1.0;
    while (uncovered(hi) > 1.0 - kTarget) hi *= 2.0;
    for (int i = 0; i < 200; ++i) (uncovered(0.5 * (lo + hi)) > 1.0 - kTarget ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
}

// Peens for `window` s (a start-up burst of `burst` x the rate in the first tenth) and forecasts.
// `burst`: the first batch's rate over the others'; `growth`: the rate grows linearly by this share of
// itself from the first batch to the last.
CoverageForecast peen_and_forecast(const Peening& p, const RegionSet& regions, double window, std::uint64_t seed, double burst = 1.0,
                                   const ReachTest& reach = kEverywhere, double growth = 0.0) {
    const double diameter = 2.0 * std::sqrt(p.dent_area / M_PI);
    auto progress = progress_of(p.cube, regions, reach, diameter / 5.0, diameter);
    Random rng(seed);
    std::vector<ForecastImpact> impacts;
    const int batches = 10;
    const double half = 0.5 * p.side;
    for (int f = 0; f < 6; ++f) {
        const int axis = f / 2;
        const double sign = f % 2 == 0 ? -1.0 : 1.0;
        for (int b = 0; b < batches; ++b) {
            // Poisson count per batch: exponential gaps.
            const double length = window / batches, rate = p.rate[static_cast<std::size_t>(f)] * p.side * p.side * (b == 0 ? burst : 1.0) *
                                                           (1.0 + growth * b / (batches - 1.0));
            for (double t = -std::log(1.0 - rng.uniform()) / rate; t < length; t += -std::log(1.0 - rng.uniform()) / rate) {
                Vec3 x;
                x[axis] = sign * half;
                x[(axis + 1) % 3] = (rng.uniform() - 0.5) * p.side;
                x[(axis + 2) % 3] = (rng.uniform() - 0.5) * p.side;
                if (rng.uniform() >= p.share(x)) continue;
                progress->add_dent(x, diameter, b * length + t);
                // The triangle it lies on: the one of its face whose closest point it is.
                std::size_t tri = 0;
                double best = 1e300;
                for (std::size_t k = 0; k < p.cube.triangle_count(); ++k) {
                    const Vec3 n = triangle_normal(p.cube, k);
                    if (n[axis] * sign < 0.99) continue;
                    const Vec3 c = (p.cube.corner(k, 0) + p.cube.corner(k, 1) + p.cube.corner(k, 2)) / 3.0;
                    if ((c - x).squaredNorm() < best) best = (c - x).squaredNorm(), tri = k;
                }
                ForecastImpact i;
                for (int k = 0; k < 3; ++k) i.point_m[k] = static_cast<float>(x[k]);
                i.triangle = static_cast<std::uint32_t>(tri);
                i.dent_area_m2 = static_cast<float>(p.dent_area);
                i.batch = static_cast<std::uint8_t>(b);
                impacts.push_back(i);
            }
        }
    }
    return forecast_coverage(*progress, p.cube, impacts, window, batches);
}

Peening cube_peening(std::vector<double> rate) {
    Peening p;
    p.side = 0.02;  // 20 mm
    p.cube = box(BoxSpec{Vec3::Constant(p.side), Vec3::Zero(), Eigen::Vector3i(4, 4, 4)});
    p.rate = std::move(rate);
    p.dent_area = M_PI * 0.125e-3 * 0.125e-3;  // a 0.25 mm dent
    return p;
}

TEST(CoverageForecast, AnEvenRateGivesTheExactTimeWithinItsInterval) {
    // mu = rate x dent area = 0.01 /s everywhere: 98 % at ln(50) / 0.01 = 391 s; 10 s of peening
    // cover 9.5 %: a forecast 39x past the window.
    const double rate = 0.01 / (M_PI * 0.125e-3 * 0.125e-3);
    const Peening p = cube_peening(std::vector<double>(6, rate));
    const double exact = exact_time(p);
    EXPECT_NEAR(exact, std::log(50.0) / 0.01, 1e-6);
    const RegionSet none(p.cube, {});
    int inside = 0;
    const int seeds = 12;
    double sum = 0.0;
    for (int seed = 1; seed <= seeds; ++seed) {
        const CoverageForecast f = peen_and_forecast(p, none, 10.0, static_cast<std::uint64_t>(seed));
        sum += f.whole.time_s;
        ASSERT_EQ(f.whole.status, AreaForecast::Status::forecast) << seed;
        EXPECT_NEAR(f.whole.time_s, exact, 0.1 * exact) << seed;
        EXPECT_LT(f.whole.low_s, f.whole.time_s);
        EXPECT_GT(f.whole.high_s, f.whole.time_s);
        inside += f.whole.low_s <= exact && exact <= f.whole.high_s;
        // Without regions, everywhere is the whole peened area.
        EXPECT_EQ(f.everywhere.time_s, f.whole.time_s);
        EXPECT_FALSE(f.summary.startup_left_out);
        EXPECT_FALSE(f.summary.rate_drifts) << seed << ": " << f.summary.rate_change;
    }
    EXPECT_GE(inside, seeds - 2) << "the 95 % interval must contain the exact time about 95 % of the time";
    // On average unbiased: the estimator's series is long enough that its truncation does not show
    // (three terms made every forecast here 1.4 % late before the smoothing correction doubled it).
    std::printf("even rate: mean forecast %+.2f %% of the exact time over %d seeds\n", 100.0 * (sum / seeds / exact - 1.0), seeds);
    EXPECT_NEAR(sum / seeds, exact, 0.015 * exact);
}

TEST(CoverageForecast, UnevenRatesArePredictedPointByPointNotAsOneRate) {
    // The top face peened 4x faster than the rest. One rate fitted to the whole (the mean) would say
    // ln(50) / mean mu; the least-peened faces decide the time instead.
    const double base = 0.01 / (M_PI * 0.125e-3 * 0.125e-3);
    const Peening p = cube_peening({base, base, base, base, base, 4.0 * base});
    RegionDesc top;
    top.name = "top";
    top.facing = FacingCondition{Vec3::UnitZ(), 1e-3};
    const RegionSet regions(p.cube, {top});
    const double exact = exact_time(p), exact_top = exact_time(p, 5);
    const double one_rate = std::log(50.0) / (0.01 * (5.0 + 4.0) / 6.0);
    EXPECT_GT(exact, 1.25 * one_rate);
    const CoverageForecast f = peen_and_forecast(p, regions, 10.0, 7);
    ASSERT_EQ(f.whole.status, AreaForecast::Status::forecast);
    EXPECT_NEAR(f.whole.time_s, exact, 0.1 * exact);
    EXPECT_LE(f.whole.low_s, exact);
    EXPECT_GE(f.whole.high_s, exact);
    ASSERT_EQ(f.regions[0].status, AreaForecast::Status::forecast);
    EXPECT_NEAR(f.regions[0].time_s, exact_top, 0.1 * exact_top);
    // Everywhere: the region and the rest of the part, which is slower (ln(50) / 0.01).
    EXPECT_EQ(f.slowest_region, CoverageForecast::kRestOfPart);
    EXPECT_NEAR(f.everywhere.time_s, std::log(50.0) / 0.01, 0.1 * std::log(50.0) / 0.01);
    EXPECT_GT(f.everywhere.time_s, f.regions[0].time_s);
}

// A rate that varies at the kernel's scale: every face but the x ones striped across x in 1.25 mm
// bands, the odd bands peened at a fifth of the rate; the bands' mean would say 98 % far sooner.
// The exact expectation counts each point's dent disc over the bands. From 80 s (h 0.74 mm) and
// 320 s (h 0.33 mm) the forecast holds it within its interval. From 20 s it does not: h is 1.2 mm,
// as wide as a band, and the forecast (about 470 s for 664 s) and its smoothing correction see the
// bands' mean (coverage_forecast.h: structure at h's own scale is not seen).
TEST(CoverageForecast, RateBandsAtTheKernelsScaleAreHeldOnceTheRunResolvesThem) {
    const double mu = 0.02;  // 1/s, dents covering a point per second in the full bands
    Peening p = cube_peening(std::vector<double>(6, mu / (M_PI * 0.125e-3 * 0.125e-3)));
    const double band = 1.25e-3, half = 0.5 * p.side, low = 0.2;  // m, m, share
    const auto share_at = [=](double x) { return static_cast<std::int64_t>(std::floor((x + half) / band)) % 2 == 0 ? 1.0 : low; };
    p.share = [=](const Vec3& x) { return share_at(x.x()); };
    // The exact expectation: a point at x is covered at mu x the share of its dent disc's area in
    // the bands, sum over the bands its disc overlaps (past the cube's edge: the x faces, full).
    const double rho = 0.125e-3;
    constexpr int kPoints = 4000, kChords = 200;
    std::vector<double> disc_share(kPoints);
    for (int i = 0; i < kPoints; ++i) {
        const double x = -half + (i + 0.5) * p.side / kPoints;
        double s = 0.0, w = 0.0;
        for (int j = 0; j < kChords; ++j) {
            const double u = -rho + (j + 0.5) * 2.0 * rho / kChords, chord = std::sqrt(rho * rho - u * u);
            s += chord * (std::abs(x + u) < half ? share_at(x + u) : 1.0);
            w += chord;
        }
        disc_share[static_cast<std::size_t>(i)] = s / w;
    }
    const auto uncovered = [&](double t) {
        double banded = 0.0;
        for (double d : disc_share) banded += std::exp(-mu * d * t);
        return (2.0 * std::exp(-mu * t) + 4.0 * banded / kPoints) / 6.0;
    };
    double lo = 0.0, hi = 1.0;
    while (uncovered(hi) > 1.0 - kTarget) hi *= 2.0;
    for (int i = 0; i < 200; ++i) (uncovered(0.5 * (lo + hi)) > 1.0 - kTarget ? lo : hi) = 0.5 * (lo + hi);
    const double exact = 0.5 * (lo + hi);
    // The bands' mean rate would say: 98 % far sooner.
    const double mean_rate_time = [&] {
        double a = 0.0, b = 1e4;
        const auto even = [&](double t) { return (2.0 * std::exp(-mu * t) + 4.0 * std::exp(-mu * 0.5 * (1.0 + low) * t)) / 6.0; };
        for (int i = 0; i < 200; ++i) (even(0.5 * (a + b)) > 1.0 - kTarget ? a : b) = 0.5 * (a + b);
        return 0.5 * (a + b);
    }();
    EXPECT_GT(exact, 1.2 * mean_rate_time);
    const RegionSet none(p.cube, {});
    const int seeds = 12;
    for (const double window : {80.0, 320.0}) {
        int inside = 0;
        for (int seed = 1; seed <= seeds; ++seed) {
            const CoverageForecast f = peen_and_forecast(p, none, window, static_cast<std::uint64_t>(seed));
            ASSERT_EQ(f.whole.status, AreaForecast::Status::forecast) << window << " s, seed " << seed;
            inside += f.whole.low_s <= exact && exact <= f.whole.high_s;
        }
        EXPECT_GE(inside, seeds - 2) << window << " s: the 95 % interval must contain the exact time about 95 % of the time";
    }
}

// A run near its target forecasts a short way, and h = sqrt(3 s a_q / (pi q)) would shrink below a
// dent radius: every uncovered point (no impact within a dent radius, by being uncovered) would see
// no impact and the forecast would say "never". The kernel keeps kHoleMargin dent radii.
TEST(CoverageForecast, ARunNearItsTargetStillGetsANumber) {
    const double rate = 0.01 / (M_PI * 0.125e-3 * 0.125e-3);
    const Peening p = cube_peening(std::vector<double>(6, rate));
    const RegionSet none(p.cube, {});
    const double exact = exact_time(p);  // 391 s
    const CoverageForecast f = peen_and_forecast(p, none, 360.0, 4);
    ASSERT_EQ(f.whole.status, AreaForecast::Status::forecast);
    EXPECT_GE(f.summary.radius_m, kHoleMargin * 0.125e-3 * (1.0 - 1e-6));
    EXPECT_NEAR(f.whole.time_s, exact, 0.03 * exact);
}

TEST(ReachBoundary, TheShareOfADiscOnItsCentresSideOfALine) {
    EXPECT_DOUBLE_EQ(disc_share_inside(0.0, 1.0), 0.5);
    EXPECT_DOUBLE_EQ(disc_share_inside(1.0, 1.0), 1.0);
    EXPECT_DOUBLE_EQ(disc_share_inside(2.0, 1.0), 1.0);
    // d = rho / 2: the segment beyond is (acos(1/2) - (1/2) sqrt(3/4)) rho^2 = (pi/3 - sqrt(3)/4) rho^2.
    EXPECT_NEAR(disc_share_inside(0.5e-3, 1e-3), 1.0 - (M_PI / 3.0 - std::sqrt(3.0) / 4.0) / M_PI, 1e-15);
    EXPECT_NEAR(disc_share_inside(0.3, 1.0), disc_share_inside(0.3e-4, 1e-4), 1e-15);  // scale-free
}

// Dents are centred where shots touch, so a point within a dent radius of surface no shot can
// reach is covered only by the dents on its own side (reach_boundary.h). Every face of the cube in
// reachable strips 0.5 mm wide between unreachable ones (a dent radius 0.125 mm: half of each strip
// lies within a radius of a boundary): a point at distance y from one edge of its strip is covered
// at the rate mu (1 - s(y) - s(0.5 mm - y)), s the disc's share beyond a line. The exact time to 98 %
// of the reachable area is 1.21 ln(50) / mu (the whole disc everywhere would say ln(50) / mu); the
// forecast from 10 s holds it (mean +1.0 % over the 6 seeds; with the whole disc near the boundary
// too, -8.0 %).
TEST(CoverageForecast, NearTheReachBoundaryOnlyTheDentsOnItsOwnSideCover) {
    const double mu = 0.01, rho = 0.125e-3, width = 0.5e-3;  // 1/s, m, m
    Peening p = cube_peening(std::vector<double>(6, mu / (M_PI * rho * rho)));
    const auto strip_coordinate = [](const Vec3& x) {
        int axis = 0;  // the face's normal axis
        for (int k = 1; k < 3; ++k)
            if (std::abs(x[k]) > std::abs(x[axis])) axis = k;
        return x[(axis + 1) % 3] + 0.5 * 0.02;  // m, from the face's edge
    };
    const auto reachable = [&](const Vec3& x) { return std::fmod(strip_coordinate(x), 2.0 * width) < width; };
    p.share = [&](const Vec3& x) { return reachable(x) ? 1.0 : 0.0; };
    const ReachTest reach = [&](const Vec3& x, std::size_t, double) { return reachable(x); };
    const auto segment = [&](double d) { return 1.0 - disc_share_inside(d, rho); };
    const auto uncovered = [&](double t) {
        const int n = 4000;
        double u = 0.0;
        for (int i = 0; i < n; ++i) {
            const double y = (i + 0.5) / n * width;
            u += std::exp(-mu * t * (1.0 - segment(y) - segment(width - y)));
        }
        return u / n;
    };
    double lo = 0.0, hi = 2000.0;
    for (int i = 0; i < 200; ++i) (uncovered(0.5 * (lo + hi)) > 1.0 - kTarget ? lo : hi) = 0.5 * (lo + hi);
    const double exact = 0.5 * (lo + hi);
    EXPECT_NEAR(exact / (std::log(50.0) / mu), 1.21, 0.01);
    const RegionSet none(p.cube, {});
    double sum = 0.0;
    int inside = 0;
    const int seeds = 6;
    for (int seed = 1; seed <= seeds; ++seed) {
        const CoverageForecast f = peen_and_forecast(p, none, 10.0, static_cast<std::uint64_t>(seed), 1.0, reach);
        ASSERT_EQ(f.whole.status, AreaForecast::Status::forecast) << seed;
        sum += f.whole.time_s;
        inside += f.whole.low_s <= exact && exact <= f.whole.high_s;
    }
    std::printf("reach strips: mean forecast %+.2f %% of the exact time over %d seeds\n", 100.0 * (sum / seeds / exact - 1.0), seeds);
    EXPECT_NEAR(sum / seeds, exact, 0.04 * exact);
    EXPECT_GE(inside, seeds - 1);
}

// The analysis bins the samples and probes the reach on every core, in fixed chunks: the forecast
// comes out the same to the bit on one thread or several.
TEST(CoverageForecast, TheSameOnAnyNumberOfThreads) {
    const double mu = 0.01, rho = 0.125e-3;  // 1/s, m: as the reach strips above, unevenly per face
    Peening p = cube_peening({mu / (M_PI * rho * rho), 2 * mu / (M_PI * rho * rho), mu / (M_PI * rho * rho), 1.5 * mu / (M_PI * rho * rho),
                              mu / (M_PI * rho * rho), 0.8 * mu / (M_PI * rho * rho)});
    const auto reachable = [](const Vec3& x) { return x.x() + 0.3 * x.y() < 4e-3; };
    p.share = [&](const Vec3& x) { return reachable(x) ? 1.0 : 0.0; };
    const ReachTest reach = [&](const Vec3& x, std::size_t, double) { return reachable(x); };
    const RegionSet none(p.cube, {});
    set_analysis_threads(1);
    const CoverageForecast one = peen_and_forecast(p, none, 10.0, 5, 1.0, reach);
    set_analysis_threads(3);
    const CoverageForecast three = peen_and_forecast(p, none, 10.0, 5, 1.0, reach);
    set_analysis_threads(0);
    ASSERT_EQ(one.whole.status, AreaForecast::Status::forecast);
    EXPECT_EQ(one.whole.time_s, three.whole.time_s);
    EXPECT_EQ(one.whole.low_s, three.whole.low_s);
    EXPECT_EQ(one.whole.high_s, three.whole.high_s);
    EXPECT_EQ(one.summary.cells, three.summary.cells);
}

// The cube's six faces as six regions (the facing direction).
RegionSet six_faces(const TriangleMesh& cube) {
    std::vector<RegionDesc> faces;
    const char* names[] = {"-x", "+x", "-y", "+y", "-z", "+z"};
    for (int f = 0; f < 6; ++f) {
        RegionDesc r;
        r.name = names[f];
        Vec3 n = Vec3::Zero();
        n[f / 2] = f % 2 == 0 ? -1.0 : 1.0;
        r.facing = FacingCondition{n, 1e-3};
        faces.push_back(r);
    }
    return RegionSet(cube, faces);
}

// Six regions alike (the faces of an evenly peened cube, as the teeth of a turning gear) reach the
// target together: everywhere is their common time (each face has 10^5 dents to go: its own run's
// spread is small). The latest of their six forecasts is late by chance, by about 1.3 of their
// standard errors (8 % each from 5 s); everywhere takes most of that off (latest_crossing.h), its
// interval holding the exact time.
TEST(CoverageForecast, EverywhereOfRegionsAlikeIsNotTheLatestOfTheirForecasts) {
    const double rate = 0.01 / (M_PI * 0.125e-3 * 0.125e-3);
    const Peening p = cube_peening(std::vector<double>(6, rate));
    const RegionSet faces = six_faces(p.cube);
    const double exact = exact_time(p, 0);
    const int seeds = 12;
    int inside = 0;
    double sum = 0.0, sum_latest = 0.0;
    for (int seed = 1; seed <= seeds; ++seed) {
        const CoverageForecast f = peen_and_forecast(p, faces, 5.0, static_cast<std::uint64_t>(seed));
        ASSERT_EQ(f.everywhere.status, AreaForecast::Status::forecast) << seed;
        double latest = 0.0;
        for (const AreaForecast& r : f.regions) latest = std::max(latest, r.time_s);
        EXPECT_GT(f.summary.everywhere_chance_excess_s, 0.0) << seed;
        EXPECT_LE(f.everywhere.low_s, f.everywhere.time_s);
        EXPECT_GE(f.everywhere.high_s, latest);
        inside += f.everywhere.low_s <= exact && exact <= f.everywhere.high_s;
        sum += f.everywhere.time_s, sum_latest += latest;
    }
    std::printf("six faces alike: everywhere %+.2f %%, the latest region's forecast %+.2f %% of the exact time over %d seeds, %d held\n",
                100.0 * (sum / seeds / exact - 1.0), 100.0 * (sum_latest / seeds / exact - 1.0), seeds, inside);
    // Measured (2026-11-28): the latest region's forecast +11.5 %, everywhere +4.2 % (the regions'
    // own forecasts +1.2 % on average from 5 s); 12 of 12 intervals held. What is left is the
    // between-region spread estimated from six values: noise often reads as a real difference,
    // and then the forecasts are not pulled together all the way.
    EXPECT_GT(sum_latest / seeds, 1.08 * exact) << "the latest of six forecasts alike is late by chance";
    EXPECT_LT(sum / seeds - exact, 0.5 * (sum_latest / seeds - exact));
    EXPECT_NEAR(sum / seeds, exact, 0.05 * exact);
    EXPECT_GE(inside, seeds - 2);
}

// One face clearly slower than the five others (0.6 x their rate): it alone sets everywhere, and
// the correction for areas alike leaves its forecast as it is.
TEST(CoverageForecast, EverywhereOfOneClearlySlowerRegionIsThatRegions) {
    const double rate = 0.01 / (M_PI * 0.125e-3 * 0.125e-3);
    Peening p = cube_peening(std::vector<double>(6, rate));
    p.rate[2] = 0.6 * rate;
    const RegionSet faces = six_faces(p.cube);
    const double exact = exact_time(p, 2);
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        const CoverageForecast f = peen_and_forecast(p, faces, 5.0, seed);
        ASSERT_EQ(f.everywhere.status, AreaForecast::Status::forecast) << seed;
        EXPECT_EQ(f.slowest_region, 2) << seed;
        EXPECT_LT(f.summary.everywhere_chance_excess_s, 0.002 * f.regions[2].time_s) << seed;
        EXPECT_NEAR(f.everywhere.time_s, f.regions[2].time_s, 0.005 * f.regions[2].time_s) << seed;
        EXPECT_LE(f.everywhere.low_s, exact) << seed;
        EXPECT_GE(f.everywhere.high_s, exact) << seed;
    }
}

TEST(CoverageForecast, AStartUpBurstIsLeftOutOfTheRates) {
    const double rate = 0.01 / (M_PI * 0.125e-3 * 0.125e-3);
    const Peening p = cube_peening(std::vector<double>(6, rate));
    const RegionSet none(p.cube, {});
    const CoverageForecast f = peen_and_forecast(p, none, 10.0, 3, 3.0);
    EXPECT_TRUE(f.summary.startup_left_out);
    EXPECT_EQ(f.summary.batches, 9);
    EXPECT_NEAR(f.summary.rate_window_s, 9.0, 1e-12);
    // The burst's extra dents (2x the rate for 1 s) are on the map: 2 s of peening saved.
    const double exact = exact_time(p) - 2.0;
    EXPECT_NEAR(f.whole.time_s, exact, 0.1 * exact);
}

// A rate that doubles over the window (a load that grows) is said to drift, with its fitted change
// (+100 % of the first batch's rate, over the mean 1.5x it: +67 %); an even one, over 12 seeds (in
// AnEvenRate...), is not.
TEST(CoverageForecast, ADriftingRateIsSaidAnEvenOneIsNot) {
    const double rate = 0.01 / (M_PI * 0.125e-3 * 0.125e-3);
    const Peening p = cube_peening(std::vector<double>(6, rate));
    const RegionSet none(p.cube, {});
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        const CoverageForecast grows = peen_and_forecast(p, none, 10.0, seed, 1.0, kEverywhere, 1.0);
        EXPECT_TRUE(grows.summary.rate_drifts) << seed;
        EXPECT_NEAR(grows.summary.rate_change, 2.0 / 3.0, 0.1) << seed;
        const CoverageForecast settles = peen_and_forecast(p, none, 10.0, seed, 1.0, kEverywhere, -0.5);
        EXPECT_TRUE(settles.summary.rate_drifts) << seed;
        EXPECT_LT(settles.summary.rate_change, -0.4) << seed;
    }
}

TEST(CoverageForecast, TooFewImpactsIsTooShortToSayAndSaysHowLongToRun) {
    const double rate = 0.01 / (M_PI * 0.125e-3 * 0.125e-3);
    const Peening p = cube_peening(std::vector<double>(6, rate));
    const RegionSet none(p.cube, {});
    const CoverageForecast f = peen_and_forecast(p, none, 0.05, 5);  // ~40 impacts over 2400 mm2
    ASSERT_EQ(f.whole.status, AreaForecast::Status::too_short);
    EXPECT_GT(f.whole.run_for_s, 0.05);
    EXPECT_GT(f.whole.high_s, kTooShortFactor * f.whole.time_s);
}

// Impacts on edges are a line process of their own (coverage_forecast.h): a small cube meshed in
// strips (its x and z faces cut into 4 mm lines 0.2 mm apart, like the facets of a curved part; its
// y faces excluded) peened only by impacts on those lines, at a known rate per metre of line. A
// point is covered at the rate lambda x the length of line within a dent radius of it, exactly; the
// forecast from 4 s must give the time of that exact expectation, within its interval. Spread over
// the faces (the areal kernel) or left out, these impacts would be wrong by far more.
TEST(CoverageForecast, ImpactsOnEdgesAreALineProcessWithTheExactFootprint) {
    const double side = 4e-3, rho = 0.125e-3, dent_area = M_PI * rho * rho;  // m, m, m2
    const TriangleMesh cube = box(BoxSpec{Vec3::Constant(side), Vec3::Zero(), Eigen::Vector3i(1, 20, 1)});
    // The 4 mm lines (along x or z), once each, with a triangle that has it.
    struct Segment {
        Vec3 a, b;
        std::uint32_t triangle;
        std::int8_t edge;
    };
    std::vector<Segment> segments;
    std::set<std::array<double, 6>> seen;
    for (std::size_t t = 0; t < cube.triangle_count(); ++t)
        for (int k = 0; k < 3; ++k) {
            Vec3 a = cube.corner(t, k), b = cube.corner(t, (k + 1) % 3);
            const Vec3 d = b - a;
            const int axes = (std::abs(d.x()) > 1e-12) + (std::abs(d.y()) > 1e-12) + (std::abs(d.z()) > 1e-12);
            if (axes != 1 || std::abs(d.y()) > 1e-12) continue;  // a diagonal, or a 0.2 mm step along y
            if (std::lexicographical_compare(b.data(), b.data() + 3, a.data(), a.data() + 3)) std::swap(a, b);
            if (!seen.insert({a.x(), a.y(), a.z(), b.x(), b.y(), b.z()}).second) continue;
            segments.push_back({a, b, static_cast<std::uint32_t>(t), static_cast<std::int8_t>(k)});
        }
    // lambda: impacts per metre of line per second; mu(x) = lambda sum over segments of the length
    // of it within rho of x (at 3D distance d from its line: the chord, cut to the segment).
    const double lambda = 800.0;  // 1/(m s)
    const auto covering_length = [&](const Vec3& x) {
        double length = 0.0;
        for (const Segment& g : segments) {
            const Vec3 u = (g.b - g.a).normalized();
            const double foot = (x - g.a).dot(u), L = (g.b - g.a).norm();
            const double d2 = (x - g.a - foot * u).squaredNorm();
            if (d2 >= rho * rho) continue;
            const double half = std::sqrt(rho * rho - d2);
            length += std::max(0.0, std::min(L, foot + half) - std::max(0.0, foot - half));
        }
        return length;
    };
    RegionDesc y_faces;
    y_faces.name = "y-faces";
    y_faces.facing = FacingCondition{Vec3::UnitY(), 1e-3};
    y_faces.exclude = true;
    RegionDesc other_y = y_faces;
    other_y.name = "other-y-face";
    other_y.facing = FacingCondition{-Vec3::UnitY(), 1e-3};
    const RegionSet none(cube, {y_faces, other_y});
    auto reference = progress_of(cube, none, kEverywhere, 2.0 * rho / 5.0, 2.0 * rho);
    std::vector<std::pair<double, double>> samples;  // (area m2, mu 1/s) of the peened samples
    reference->map().for_each_sample_row(
        [&](std::size_t t, const Vec3& first, const Vec3& step, std::int64_t count, double area, std::int64_t) {
            if (std::abs(triangle_normal(cube, t).y()) > 0.5) return;  // excluded
            for (std::int64_t i = 0; i < count; ++i)
                samples.emplace_back(area, lambda * covering_length(first + static_cast<double>(i) * step));
        });
    const auto uncovered = [&](double t) {
        double u = 0.0, total = 0.0;
        for (const auto& [area, mu] : samples) u += area * std::exp(-mu * t), total += area;
        return u / total;
    };
    double lo = 0.0, hi = 1.0;
    while (uncovered(hi) > 1.0 - kTarget) hi *= 2.0;
    for (int i = 0; i < 100; ++i) (uncovered(0.5 * (lo + hi)) > 1.0 - kTarget ? lo : hi) = 0.5 * (lo + hi);
    const double exact = 0.5 * (lo + hi);
    EXPECT_GT(exact, 15.0);  // far past the 4 s window
    const double window = 4.0;
    const int batches = 10, seeds = 6;
    int inside = 0;
    double mean = 0.0;
    for (int seed = 1; seed <= seeds; ++seed) {
        auto progress = progress_of(cube, none, kEverywhere, 2.0 * rho / 5.0, 2.0 * rho);
        Random rng(static_cast<std::uint64_t>(seed));
        std::vector<ForecastImpact> impacts;
        for (const Segment& g : segments) {
            const double rate = lambda * (g.b - g.a).norm();  // 1/s on this segment
            for (double t = -std::log(1.0 - rng.uniform()) / rate; t < window; t += -std::log(1.0 - rng.uniform()) / rate) {
                const Vec3 x = g.a + rng.uniform() * (g.b - g.a);
                progress->add_dent(x, 2.0 * rho, t);
                ForecastImpact i;
                for (int k = 0; k < 3; ++k) i.point_m[k] = static_cast<float>(x[k]);
                i.triangle = g.triangle;
                i.edge = g.edge;
                i.dent_area_m2 = static_cast<float>(dent_area);
                i.batch = static_cast<std::uint8_t>(std::min(batches - 1, static_cast<int>(t / window * batches)));
                impacts.push_back(i);
            }
        }
        const CoverageForecast f = forecast_coverage(*progress, cube, impacts, window, batches);
        EXPECT_EQ(f.summary.face_impacts, 0u);
        EXPECT_EQ(f.summary.edge_impacts, impacts.size());
        ASSERT_EQ(f.whole.status, AreaForecast::Status::forecast) << seed;
        EXPECT_NEAR(f.whole.time_s, exact, 0.15 * exact) << seed;  // ~10 impacts per line: a noisy 5x extrapolation
        mean += f.whole.time_s / seeds;
        inside += f.whole.low_s <= exact && exact <= f.whole.high_s;
    }
    EXPECT_NEAR(mean, exact, 0.07 * exact);  // measured: +5 % (20.2 s exact; the forecasts 20.2-22.6 s)
    EXPECT_GE(inside, seeds - 1) << "the 95 % interval must contain the exact time";
}

TEST(MeshChecks, APointOnAnEdgeOfItsTriangle) {
    const TriangleMesh cube = box(BoxSpec{Vec3::Ones(), Vec3::Zero(), Eigen::Vector3i(1, 1, 1)});
    const Vec3 a = cube.corner(0, 0), b = cube.corner(0, 1), c = cube.corner(0, 2);
    EXPECT_TRUE(on_triangle_edge(cube, 0, 0.5 * (a + b)));
    EXPECT_TRUE(on_triangle_edge(cube, 0, a));
    EXPECT_FALSE(on_triangle_edge(cube, 0, (a + b + c) / 3.0));
    EXPECT_FALSE(on_triangle_edge(cube, 0, 0.5 * (a + b) + 1e-5 * ((a + b + c) / 3.0 - 0.5 * (a + b)).normalized()));
}

}  // namespace
}  // namespace peensim
