// The ballistic path and the swept-sphere box spans built on it: exact bounds against dense
// sampling, and spans that are conservative (every moment the centre is within R of the box along
// every axis lies inside) yet tight (their ends are such moments, up to the pad).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "kernels/swept_sphere_box.h"
#include "kernels/trajectory.h"

namespace peensim {
namespace {

TEST(EventTrajectory, PositionVelocityAndRebasing) {
    const Trajectory path{Vec3(1, 2, 3), Vec3(0.5, -1, 2), Vec3(0, 0, -9.81), 0.25};
    const double u = 0.4;
    EXPECT_NEAR((path.position(0.25 + u) - Vec3(1 + 0.5 * u, 2 - u, 3 + 2 * u - 0.5 * 9.81 * u * u)).norm(), 0.0, 1e-15);
    EXPECT_NEAR((path.velocity(0.25 + u) - Vec3(0.5, -1, 2 - 9.81 * u)).norm(), 0.0, 1e-15);
    const Trajectory later = path.rebased(0.9);
    for (double t : {-1.0, 0.0, 0.5, 2.0}) {
        EXPECT_NEAR((later.position(t) - path.position(t)).norm(), 0.0, 1e-14);
        EXPECT_NEAR((later.velocity(t) - path.velocity(t)).norm(), 0.0, 1e-14);
    }
}

TEST(EventTrajectory, BoundsAndTopSpeedMatchSampling) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto random_vec = [&](double s) -> Vec3 { return Vec3(unit(rng), unit(rng), unit(rng)) * s; };
    for (int trial = 0; trial < 200; ++trial) {
        const Trajectory path{random_vec(0.01), random_vec(2.0), random_vec(10.0), unit(rng)};
        const double ta = unit(rng), tb = ta + 0.5 * (unit(rng) + 1.0);
        Vec3 lo, hi;
        path.bounds(ta, tb, lo, hi);
        Vec3 slo = Vec3::Constant(1e300), shi = Vec3::Constant(-1e300);
        double top = 0.0;
        for (int i = 0; i <= 20000; ++i) {
            const double t = ta + (tb - ta) * i / 20000.0;
            slo = slo.cwiseMin(path.position(t));
            shi = shi.cwiseMax(path.position(t));
            top = std::max(top, path.velocity(t).norm());
        }
        // Exact bounds contain every sample and are reached to within the sampling step.
        for (int k = 0; k < 3; ++k) {
            EXPECT_LE(lo[k], slo[k] + 1e-14);  // positions of a few metres, rounded
            EXPECT_GE(hi[k], shi[k] - 1e-14);
            EXPECT_NEAR(lo[k], slo[k], 1e-6);
            EXPECT_NEAR(hi[k], shi[k], 1e-6);
        }
        EXPECT_NEAR(path.max_speed(ta, tb), top, 1e-12);
    }
}

// Within R (plus slack) of the box along every axis.
bool within_reach(const Vec3& p, const Vec3& lo, const Vec3& hi, double reach) {
    for (int k = 0; k < 3; ++k)
        if (p[k] < lo[k] - reach || p[k] > hi[k] + reach) return false;
    return true;
}

TEST(EventSweptSphere, SpansAreConservativeAndTight) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto random_vec = [&](double s) -> Vec3 { return Vec3(unit(rng), unit(rng), unit(rng)) * s; };
    constexpr double R = 1e-3;
    int entered = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        // Gravity along z, or in a random direction (a tilted mesh frame); a few without. Half the
        // paths are slow and long, so that they curve back through the box.
        const Vec3 g = trial % 5 == 0 ? Vec3::Zero() : (trial % 2 ? Vec3(0, 0, -9.81) : Vec3(random_vec(1.0).normalized() * 9.81));
        const bool slow = trial % 4 < 2;
        const Vec3 c = random_vec(0.008), half = (random_vec(0.003).cwiseAbs());
        const Vec3 start = random_vec(0.01);
        const Vec3 aim = (c + random_vec(0.006) - start).normalized();
        const Trajectory path{start, aim * (slow ? 0.3 : 1.0) + (slow ? Vec3(random_vec(0.3)) : Vec3::Zero()), g, 0.0};
        const Vec3 lo = c - half, hi = c + half;
        const double t_begin = 0.01 * unit(rng), t_end = t_begin + (slow ? 0.2 : 0.05);
        const SweptSphere swept(path, R, t_begin, t_end);
        TimeSpan span;
        const bool any = swept.span(lo, hi, span);
        double first = 1e300, last = -1e300;
        constexpr int kSamples = 20000;
        for (int i = 0; i <= kSamples; ++i) {
            const double t = t_begin + (t_end - t_begin) * i / kSamples;
            const bool inside = within_reach(path.position(t), lo, hi, R);
            if (inside) {
                first = std::min(first, t);
                last = std::max(last, t);
            }
        }
        if (first > last) {
            // Never within reach at a sample; then any span must be a brief one between samples.
            if (any) {
                EXPECT_LT(span.last - span.first, 2.0 * (t_end - t_begin) / kSamples) << trial;
            }
            continue;
        }
        ++entered;
        ASSERT_TRUE(any) << trial;
        EXPECT_LE(span.first, first) << trial;
        EXPECT_GE(span.last, last) << trial;
        // The ends are within reach of the box grown by the pad (and an ulp).
        EXPECT_TRUE(within_reach(path.position(span.first), lo, hi, R + swept.pad() + 1e-15)) << trial;
        EXPECT_TRUE(within_reach(path.position(span.last), lo, hi, R + swept.pad() + 1e-15)) << trial;
        EXPECT_GE(span.first, t_begin);
        EXPECT_LE(span.last, t_end);
    }
    EXPECT_GT(entered, 300);
}

TEST(EventSweptSphere, AThrowThroughASlabVisitsItTwice) {
    // Thrown up through a thin horizontal slab z in [z1, z2] and falling back: the span runs from
    // the way up (centre at z1 - R) to the way down (centre at z1 - R again); in between the
    // centre rises above z2 + R and leaves the grown slab.
    constexpr double R = 1e-3, g = 9.81, vz = 1.0, z1 = 0.01, z2 = 0.011;
    const Trajectory path{Vec3(0, 0, 0), Vec3(0.02, -0.01, vz), Vec3(0, 0, -g), 0.0};
    const SweptSphere swept(path, R, 0.0, 1.0);
    TimeSpan span;
    ASSERT_TRUE(swept.span(Vec3(-1, -1, z1), Vec3(1, 1, z2), span));
    const double h = z1 - R - swept.pad();
    const double up = (vz - std::sqrt(vz * vz - 2 * g * h)) / g, down = (vz + std::sqrt(vz * vz - 2 * g * h)) / g;
    EXPECT_NEAR(span.first, up, 1e-12);
    EXPECT_NEAR(span.last, down, 1e-12);
    // A slab above the apex is never reached; one straddling it is visited once.
    const double apex = vz * vz / (2 * g);
    EXPECT_FALSE(swept.span(Vec3(-1, -1, apex + R + 1e-6), Vec3(1, 1, apex + 0.01), span));
    EXPECT_TRUE(swept.span(Vec3(-1, -1, apex - 1e-3), Vec3(1, 1, apex + 0.01), span));
}

TEST(EventSweptSphere, SlabSpansMatchSampling) {
    // Slabs lo <= n . x <= hi of random orientation (a triangle's plane when lo = hi).
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto random_vec = [&](double s) -> Vec3 { return Vec3(unit(rng), unit(rng), unit(rng)) * s; };
    constexpr double R = 1e-3;
    int entered = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const Trajectory path{random_vec(0.01), random_vec(0.5), Vec3(0, 0, -9.81), 0.0};
        const Vec3 n = random_vec(1.0).normalized();
        const double lo = 0.008 * unit(rng), hi = lo + (trial % 2 ? 0.0 : 0.002 * (unit(rng) + 1.0));
        const SweptSphere swept(path, R, 0.0, 0.1);
        TimeSpan span;
        const bool any = swept.slab_span(n, lo, hi, span);
        double first = 1e300, last = -1e300;
        for (int i = 0; i <= 20000; ++i) {
            const double t = 0.1 * i / 20000.0, x = n.dot(path.position(t));
            if (x >= lo - R && x <= hi + R) {
                first = std::min(first, t);
                last = std::max(last, t);
            }
        }
        if (first > last) continue;
        ++entered;
        ASSERT_TRUE(any) << trial;
        EXPECT_LE(span.first, first);
        EXPECT_GE(span.last, last);
        EXPECT_GT(span.first, first - 2.0 * 0.1 / 20000.0 - 1e-5);  // tight, up to a sample and the pad
        EXPECT_LT(span.last, last + 2.0 * 0.1 / 20000.0 + 1e-5);
    }
    EXPECT_GT(entered, 300);
}

TEST(EventSweptSphere, GravityResidueOnAnAxisIsHandledAsLinear) {
    // Gravity rotated into a frame leaves ~1e-15 m/s^2 on the other axes; 1 / (2 h) would be huge.
    const Trajectory path{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1e-15, -2e-16, -9.81), 0.0};
    const SweptSphere swept(path, 1e-3, 0.0, 0.05);
    TimeSpan span;
    ASSERT_TRUE(swept.span(Vec3(0.02, -0.01, -0.05), Vec3(0.03, 0.01, 0.05), span));
    EXPECT_NEAR(span.first, 0.019, 1e-8);
    EXPECT_NEAR(span.last, 0.031, 1e-8);
}

TEST(EventSweptSphere, ShorteningEndsTheSweep) {
    const Trajectory path{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3::Zero(), 0.0};
    SweptSphere swept(path, 1e-3, 0.0, 1.0);
    const Vec3 lo(0.5, -0.01, -0.01), hi(0.6, 0.01, 0.01);
    TimeSpan span;
    ASSERT_TRUE(swept.span(lo, hi, span));
    EXPECT_NEAR(span.first, 0.499, 1e-8);
    EXPECT_NEAR(span.last, 0.601, 1e-8);
    swept.shorten(0.55);
    ASSERT_TRUE(swept.span(lo, hi, span));
    EXPECT_NEAR(span.last, 0.55, 1e-15);
    swept.shorten(0.4);
    EXPECT_FALSE(swept.span(lo, hi, span));
    EXPECT_EQ(swept.t_end(), 0.4);
}

}  // namespace
}  // namespace peensim
