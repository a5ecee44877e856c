// The root finder behind every exact time of impact, checked against polynomials built from known
// factors: simple, double and quadruple roots, leading coefficients that vanish, roots on the ends
// of the interval, and the kind of each root (which side of zero p lies on around it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "kernels/polynomial_roots.h"

namespace peensim {
namespace {

// The polynomial scale * prod (t - r_i), coefficients in increasing power.
Polynomial from_roots(const std::vector<double>& roots, double scale = 1.0) {
    Polynomial p;
    p.c = {scale, 0, 0, 0, 0};
    p.degree = 0;
    for (double r : roots) {
        for (int i = p.degree + 1; i >= 0; --i) {
            const double lower = i > 0 ? p.c[static_cast<std::size_t>(i - 1)] : 0.0;
            p.c[static_cast<std::size_t>(i)] = lower - r * p.c[static_cast<std::size_t>(i)];
        }
        ++p.degree;
    }
    return p;
}

std::vector<PolynomialRoot> roots_of(const Polynomial& p, double a, double b) {
    PolynomialRoots r;
    real_roots_in(p, a, b, r);
    return {r.root.begin(), r.root.begin() + r.count};
}

void expect_near_relative(double got, double want, double rel = 1e-12) {
    EXPECT_NEAR(got, want, rel * std::max(std::fabs(want), 1e-300)) << "want " << want;
}

TEST(EventPolynomialRoots, FromFactorsBuildsTheRightCoefficients) {
    const Polynomial p = from_roots({1.0, 2.0});  // t^2 - 3 t + 2
    EXPECT_EQ(p.degree, 2);
    EXPECT_DOUBLE_EQ(p.c[0], 2.0);
    EXPECT_DOUBLE_EQ(p.c[1], -3.0);
    EXPECT_DOUBLE_EQ(p.c[2], 1.0);
}

TEST(EventPolynomialRoots, FourSimpleRootsAlternateFallingAndRising) {
    const Polynomial p = from_roots({0.1, 0.35, 0.7, 0.9});
    const auto r = roots_of(p, 0.0, 1.0);
    ASSERT_EQ(r.size(), 4u);
    const double want[] = {0.1, 0.35, 0.7, 0.9};
    for (int i = 0; i < 4; ++i) expect_near_relative(r[static_cast<std::size_t>(i)].t, want[i]);
    EXPECT_EQ(r[0].kind, RootKind::falling);  // p(0) > 0 for an even count of positive factors
    EXPECT_EQ(r[1].kind, RootKind::rising);
    EXPECT_EQ(r[2].kind, RootKind::falling);
    EXPECT_EQ(r[3].kind, RootKind::rising);
}

TEST(EventPolynomialRoots, OnlyRootsInsideTheIntervalAreReported) {
    const Polynomial p = from_roots({-2.0, 0.25, 0.5, 3.0});
    const auto r = roots_of(p, 0.0, 1.0);
    ASSERT_EQ(r.size(), 2u);
    expect_near_relative(r[0].t, 0.25);
    expect_near_relative(r[1].t, 0.5);
}

TEST(EventPolynomialRoots, DoubleRootIsFoundAsATouch) {
    // (t - 0.3)^2 (t - 0.8) (t + 2): p touches zero at 0.3 without changing sign.
    const Polynomial p = from_roots({0.3, 0.3, 0.8, -2.0});
    const auto r = roots_of(p, 0.0, 1.0);
    ASSERT_EQ(r.size(), 2u);
    expect_near_relative(r[0].t, 0.3);
    EXPECT_EQ(r[0].kind, RootKind::touch_from_below);  // p < 0 on both sides (t - 0.8 < 0, t + 2 > 0)
    expect_near_relative(r[1].t, 0.8);
    EXPECT_EQ(r[1].kind, RootKind::rising);

    const auto above = roots_of(from_roots({0.3, 0.3}, 2.5), 0.0, 1.0);
    ASSERT_EQ(above.size(), 1u);
    expect_near_relative(above[0].t, 0.3);
    EXPECT_EQ(above[0].kind, RootKind::touch_from_above);
}

TEST(EventPolynomialRoots, QuadrupleRootIsOneRoot) {
    for (double r0 : {1.0, 0.3, 1.7e-3}) {
        const Polynomial p = from_roots({r0, r0, r0, r0});
        const auto r = roots_of(p, 0.0, 2.0 * r0);
        ASSERT_EQ(r.size(), 1u) << r0;
        expect_near_relative(r[0].t, r0);
        EXPECT_EQ(r[0].kind, RootKind::touch_from_above);
    }
}

TEST(EventPolynomialRoots, TripleRootChangesSign) {
    const Polynomial p = from_roots({0.4, 0.4, 0.4, 5.0});  // (t - 0.4)^3 (t - 5): + to - at 0.4... mirrored
    const auto r = roots_of(p, 0.0, 1.0);
    ASSERT_EQ(r.size(), 1u);
    EXPECT_NEAR(r[0].t, 0.4, 1e-5);           // a triple root is only defined to about eps^(1/3)
    EXPECT_EQ(r[0].kind, RootKind::falling);  // (t-0.4)^3 (t-5): positive before, negative after
}

TEST(EventPolynomialRoots, VanishingLeadingCoefficientsDropTheDegree) {
    Polynomial p = from_roots({0.2, 0.6});
    p.degree = 4;  // c3 = c4 = 0: still a quadratic
    auto r = roots_of(p, 0.0, 1.0);
    ASSERT_EQ(r.size(), 2u);
    expect_near_relative(r[0].t, 0.2);
    expect_near_relative(r[1].t, 0.6);

    // Tiny leading coefficients: the extra roots lie far outside, the near ones are unchanged.
    Polynomial q = from_roots({0.2, 0.6, 0.9});
    q.degree = 4;
    q.c[4] = 1e-30;
    r = roots_of(q, 0.0, 1.0);
    ASSERT_EQ(r.size(), 3u);
    expect_near_relative(r[0].t, 0.2);
    expect_near_relative(r[1].t, 0.6);
    expect_near_relative(r[2].t, 0.9);

    // Linear and constant polynomials.
    Polynomial line;
    line.degree = 1;
    line.c = {-0.75, 2.5, 0, 0, 0};
    r = roots_of(line, 0.0, 1.0);
    ASSERT_EQ(r.size(), 1u);
    expect_near_relative(r[0].t, 0.3);
    Polynomial constant;
    constant.c = {3.0, 0, 0, 0, 0};
    EXPECT_TRUE(roots_of(constant, 0.0, 1.0).empty());
}

TEST(EventPolynomialRoots, RootsAtTheEndsOfTheInterval) {
    const Polynomial p = from_roots({0.25, 0.75});  // negative between its roots
    const auto r = roots_of(p, 0.25, 0.75);
    ASSERT_EQ(r.size(), 2u);
    EXPECT_EQ(r[0].t, 0.25);
    EXPECT_EQ(r[0].kind, RootKind::falling);  // p < 0 just after the start
    EXPECT_EQ(r[1].t, 0.75);
    EXPECT_EQ(r[1].kind, RootKind::rising);  // p < 0 just before the end

    // A degenerate interval [a, a]: a root exactly there or nothing.
    EXPECT_EQ(roots_of(p, 0.25, 0.25).size(), 1u);
    EXPECT_TRUE(roots_of(p, 0.5, 0.5).empty());
    EXPECT_TRUE(roots_of(p, 0.6, 0.5).empty());  // empty interval
}

TEST(EventPolynomialRoots, NearDoubleRootsSplitOrTouchByRounding) {
    // (t - 0.5)^2 - d: two roots 0.5 +- sqrt(d) while d is resolvable, none for d < 0.
    Polynomial p = from_roots({0.5, 0.5});
    p.c[0] -= 1e-10;
    auto r = roots_of(p, 0.0, 1.0);
    ASSERT_EQ(r.size(), 2u);
    // Rounding of c0 alone (~eps / 4) moves these roots by ~1e-11: the slope there is only 2e-5.
    EXPECT_NEAR(r[0].t, 0.5 - 1e-5, 2e-11);
    EXPECT_NEAR(r[1].t, 0.5 + 1e-5, 2e-11);
    p.c[0] += 2e-10;  // minimum +1e-10: clearly no root
    EXPECT_TRUE(roots_of(p, 0.0, 1.0).empty());
}

TEST(EventPolynomialRoots, FirstRootInStopsAtTheEarliestAccepted) {
    const Polynomial p = from_roots({0.1, 0.35, 0.7, 0.9}, -1.0);  // negative at 0: rises first
    PolynomialRoot r;
    ASSERT_TRUE(first_root_in(p, 0.0, 1.0, r));
    expect_near_relative(r.t, 0.1);
    EXPECT_EQ(r.kind, RootKind::rising);
    ASSERT_TRUE(first_root_in(p, 0.0, 1.0, r, RootFilter::entering));
    expect_near_relative(r.t, 0.35);
    EXPECT_EQ(r.kind, RootKind::falling);
    EXPECT_FALSE(first_root_in(p, 0.36, 0.69, r));
    // A touch from above counts as entering; one from below does not.
    ASSERT_TRUE(first_root_in(from_roots({0.3, 0.3, 0.6}, -1.0), 0.0, 1.0, r, RootFilter::entering));
    expect_near_relative(r.t, 0.3);  // -(t-0.3)^2 (t-0.6) >= 0 around 0.3
    EXPECT_EQ(r.kind, RootKind::touch_from_above);
    EXPECT_FALSE(first_root_in(from_roots({0.3, 0.3}, -1.0), 0.0, 1.0, r, RootFilter::entering));
}

TEST(EventPolynomialRoots, RandomQuarticsMatchTheirFactors) {
    // Time-like scales: roots of 1e-4..1 s. Well separated roots must come out to 1e-12 relative;
    // close ones to what the rounding of the coefficients allows (their condition number).
    std::mt19937_64 rng(7);
    int well_separated = 0, close = 0;
    for (double scale : {1e-4, 1e-2, 1e-1, 1.0}) {
        std::uniform_real_distribution<double> u(0.0, scale);
        for (int trial = 0; trial < 2000; ++trial) {
            std::vector<double> r = {u(rng), u(rng), u(rng), u(rng)};
            std::sort(r.begin(), r.end());
            double gap = scale;
            for (std::size_t i = 0; i + 1 < 4; ++i) gap = std::min(gap, r[i + 1] - r[i]);
            if (gap < 1e-4 * scale) continue;
            const Polynomial p = from_roots(r, trial % 2 ? 3.7 : -0.2);
            const auto got = roots_of(p, 0.0, scale);
            ASSERT_EQ(got.size(), 4u);
            for (std::size_t i = 0; i < 4; ++i) {
                double slope = 1.0, magnitude = 0.0, power = 1.0;
                for (std::size_t j = 0; j < 4; ++j)
                    if (j != i) slope *= r[i] - r[j];
                for (std::size_t k = 0; k <= 4; ++k, power *= r[i]) magnitude += std::fabs(p.c[k]) * power;
                slope *= p.c[4];
                const double conditioned = 32.0 * 2.2e-16 * magnitude / std::fabs(slope);
                const double tolerance = gap > 0.1 * scale ? 1e-12 * r[i] : std::max(1e-12 * r[i], conditioned);
                EXPECT_NEAR(got[i].t, r[i], tolerance);
            }
            ++(gap > 0.1 * scale ? well_separated : close);
        }
    }
    EXPECT_GT(well_separated, 1000);
    EXPECT_GT(close, 1000);
}

}  // namespace
}  // namespace peensim
