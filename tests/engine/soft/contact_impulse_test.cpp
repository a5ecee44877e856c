// The soft pool's half-step normal impulse (engine/soft/contact_impulse.h) against a brute-force
// integration of the same weighted force along the same path.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "contact/hertz_mindlin.h"
#include "contact/linear_spring_dashpot_law.h"
#include "engine/soft/contact_impulse.h"

namespace peensim::testing {
namespace {

contact::SoftPair steel_on_steel(double e) {
    const double m = 7800.0 * 4.0 / 3.0 * M_PI * 1e-9;  // kg, a 2 mm steel shot
    const contact::ElasticMaterial steel{200e9, 0.3};
    return contact::hertz_pair(steel, steel, 1e-3, contact::kInfinite, m, contact::kInfinite, e, 0.0);
}

// The same pair with the linear spring-dashpot law (stiffness at a characteristic speed of 2 m/s):
// a force of other powers (1 and 0: the damper's force jumps where the contact begins).
contact::SoftPair linear_steel_on_steel(double e) {
    const double m = 7800.0 * 4.0 / 3.0 * M_PI * 1e-9;  // kg
    const contact::ElasticMaterial steel{200e9, 0.3};
    return contact::linear_spring_dashpot_pair(steel, steel, 1e-3, contact::kInfinite, m, contact::kInfinite, e, 0.0, 2.0, 1.0);
}

// Either law's pair.
contact::SoftPair pair_of(bool linear, double e) { return linear ? linear_steel_on_steel(e) : steel_on_steel(e); }

// Gauss-Legendre on [a, b] with 16 points (nodes by Newton's iteration on the Legendre polynomial).
double gauss16(const std::function<double(double)>& f, double a, double b) {
    static std::vector<std::pair<double, double>> rule;
    if (rule.empty()) {
        const int n = 16;
        for (int i = 1; i <= n; ++i) {
            double x = std::cos(M_PI * (i - 0.25) / (n + 0.5)), dp = 1.0;
            for (int it = 0; it < 100; ++it) {
                double p0 = 1.0, p1 = x;
                for (int j = 2; j <= n; ++j) {
                    const double p2 = ((2.0 * j - 1.0) * x * p1 - (j - 1.0) * p0) / j;
                    p0 = p1, p1 = p2;
                }
                dp = n * (x * p1 - p0) / (x * x - 1.0);
                x -= p1 / dp;
            }
            rule.emplace_back(x, 2.0 / ((1.0 - x * x) * dp * dp));
        }
    }
    double sum = 0.0;
    for (const auto& [x, w] : rule) sum += w * f(0.5 * (a + b) + 0.5 * (b - a) * x);
    return 0.5 * (b - a) * sum;
}

// A piece between two roots (or a root and an end), in 2 x 80 intervals halving towards each end:
// the delta^1/4 and delta^3/2 ends are resolved without any change of variable.
double graded(const std::function<double(double)>& f, double a, double b) {
    const double m = 0.5 * (a + b);
    double sum = 0.0;
    for (int k = 0; k < 80; ++k) {
        const double outer = std::ldexp(m - a, -k), inner = std::ldexp(m - a, -k - 1);
        sum += gauss16(f, a + inner, a + outer) + gauss16(f, b - outer, b - inner);
    }
    return sum;
}

// The x component of the impulse, brute force: the overlap's sign changes found on a fine grid and
// by bisection, each positive piece integrated on intervals halving towards its ends.
double brute_force(const contact::SoftPair& pair, const ContactPath& path, double h) {
    const double H = std::abs(h), sign = h < 0.0 ? -1.0 : 1.0;
    const auto overlap = [&](double tau) {
        double d, r;
        contact_path_at(pair, path, h, tau, d, r);
        return d;
    };
    const auto weighted = [&](double s) {
        const double tau = sign * s;
        double delta, rate;
        contact_path_at(pair, path, h, tau, delta, rate);
        if (!(delta > 0.0)) return 0.0;
        const Vec3 n = (path.normal + tau * path.turn_per_s).normalized();
        return (1.0 - s / H) * contact::soft_normal_force(pair, delta, rate) * n.x();
    };
    std::vector<double> cuts{0.0};
    const int grid = 4000;
    for (int k = 0; k < grid; ++k) {
        double a = H * k / grid, b = H * (k + 1) / grid;
        const double oa = overlap(sign * a), ob = overlap(sign * b);
        if ((oa > 0.0) == (ob > 0.0)) continue;
        for (int it = 0; it < 200; ++it) {
            const double m = 0.5 * (a + b);
            ((overlap(sign * m) > 0.0) == (oa > 0.0) ? a : b) = m;
        }
        cuts.push_back(0.5 * (a + b));
    }
    cuts.push_back(H);
    double sum = 0.0;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double a = cuts[k], b = cuts[k + 1], m = 0.5 * (a + b);
        if (!(overlap(sign * m) > 0.0)) continue;
        sum += graded(weighted, a, b);
    }
    return sum;
}

// The quadrature and the roots, on 400 random paths (most touching: beginning, ending, or both, or
// deep in a contact; elastic or damped; turning normals): against 2 x 80 intervals halving
// towards every root of the same path, each with 16 Gauss points, the impulse is right to 1e-8 of
// the impulse of a 10 um overlap over the half step (measured 3e-9: 4 Gauss points deep in a
// contact whose path bends hard; accelerations up to 1e6 m/s2 here).
// Both laws' forces (Hertz's powers 3/2 and 1/4; the linear law's 1 and 0).
class SoftContactImpulseLaws : public ::testing::TestWithParam<bool> {};

TEST_P(SoftContactImpulseLaws, MatchesABruteForceIntegrationWhereverTheContactBeginsOrEnds) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double worst = 0.0;
    int touching = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const contact::SoftPair pair = pair_of(GetParam(), trial % 2 ? 1.0 : 0.8);
        // A contact of ~2 m/s: overlaps up to ~10 um, steps of 0.05-1 us, accelerations up to 1e6 m/s2.
        const double h = (0.05 + u(rng)) * 1e-6 * (u(rng) < 0.5 ? -1.0 : 1.0);
        ContactPath p;
        p.rate_m_per_s = (u(rng) - 0.5) * 8.0;
        p.overlap_m = (u(rng) - 0.3) * 3.0 * std::abs(p.rate_m_per_s * h) + (trial % 7 == 0 ? 0.0 : (u(rng) < 0.3 ? 1e-5 * u(rng) : 0.0));
        if (trial % 11 == 0) p.overlap_m = 0.0;  // begins exactly at the node
        p.outer_accel_m_per_s2 = (u(rng) - 0.7) * 1e6;
        p.normal = Vec3(1.0, 0.3, -0.2).normalized();
        if (trial % 3 == 0) p.turn_per_s = Vec3(0.0, 1.0, 0.5) * 2e3;
        const double expected = brute_force(pair, p, h);
        const double got = half_step_impulse(pair, p, h).near.x();
        // The scale: the force of a 10 um overlap over the half step.
        const double scale = contact::soft_normal_force(pair, 1e-5, 0.0) * std::abs(h);
        if (expected != 0.0) ++touching;
        worst = std::max(worst, std::abs(got - expected) / scale);
        EXPECT_NEAR(got, expected, 1e-8 * scale)
            << trial << ": e " << (trial % 2 ? 1.0 : 0.8) << ", h " << h << " s, overlap " << p.overlap_m << " m, rate " << p.rate_m_per_s
            << " m/s, accel " << p.outer_accel_m_per_s2 << " m/s2";
    }
    std::cout << "[ impulse  ] " << (GetParam() ? "linear" : "hertz") << ": " << touching << " of 400 paths touching; worst error " << worst
              << " of the scale\n";
    EXPECT_GT(touching, 200);
}

TEST_P(SoftContactImpulseLaws, AConstantForceGivesHalfItsImpulse) {
    // Deep in a contact at rest the force is constant: each half hat weighs it by h / 2.
    const contact::SoftPair pair = pair_of(GetParam(), 1.0);
    ContactPath p;
    p.overlap_m = 5e-6;
    p.outer_accel_m_per_s2 = contact::soft_normal_force(pair, 5e-6, 0.0) / pair.m_star_kg;  // held there
    const Vec3 j = half_step_impulse(pair, p, 1e-7).near;
    EXPECT_NEAR(j.z(), contact::soft_normal_force(pair, 5e-6, 0.0) * 0.5e-7, 1e-9 * j.z());
    EXPECT_NEAR(half_step_impulse(pair, p, -1e-7).near.z(), j.z(), 1e-12 * j.z());
    p.overlap_m = -1e-9;  // a gap that stays open
    p.outer_accel_m_per_s2 = 0.0;
    EXPECT_EQ(half_step_impulse(pair, p, 1e-7).near, Vec3::Zero());
}

}  // namespace
}  // namespace peensim::testing

namespace peensim::testing {
namespace {

// The path along which the impulse is integrated against the true motion of an isolated contact
// (delta'' = A - F(delta, delta') / m*, integrated by RK4 in 1e-4 of the half step) from the same
// node, a whole step of a contact of 2 m/s at 20 steps per contact on, from nodes all along the
// contact and just outside it: the closed-form path is off by a few 1e-6 of the largest overlap
// (measured 2.2e-6 elastic, 4.9e-6 at e 0.8; its terms of the fifth order in the time, odd: the
// two half steps' errors around a node cancel to the next order), where the overlap's quadratic
// Taylor polynomial from the node was off by 4.6e-5.
TEST_P(SoftContactImpulseLaws, ThePathFollowsAnIsolatedContact) {
    for (const double e : {1.0, 0.8}) {
        const contact::SoftPair pair = pair_of(GetParam(), e);
        const double v = 2.0, H = contact::soft_contact_duration(pair, v) / 20.0, g = 9.81;
        const auto accel = [&](double d, double r) { return g - contact::soft_normal_force(pair, d, r) / pair.m_star_kg; };
        // The contact itself, by RK4 in fine steps from its touch, sampled as nodes every H.
        std::vector<std::pair<double, double>> nodes;  // (delta, rate)
        double d = -0.3 * v * H, r = v, top = 0.0;
        const int fine = 10000;
        const double dt = H / fine;
        for (int step = 0; nodes.size() < 30 && (step < fine || d > -v * H); ++step) {
            if (step % fine == 0) nodes.emplace_back(d, r);
            const double k1d = r, k1r = accel(d, r);
            const double k2d = r + 0.5 * dt * k1r, k2r = accel(d + 0.5 * dt * k1d, r + 0.5 * dt * k1r);
            const double k3d = r + 0.5 * dt * k2r, k3r = accel(d + 0.5 * dt * k2d, r + 0.5 * dt * k2r);
            const double k4d = r + dt * k3r, k4r = accel(d + dt * k3d, r + dt * k3r);
            d += dt / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d);
            r += dt / 6.0 * (k1r + 2.0 * k2r + 2.0 * k3r + k4r);
            top = std::max(top, d);
        }
        double worst = 0.0;
        for (std::size_t k = 0; k + 1 < nodes.size(); ++k) {
            ContactPath p;
            p.overlap_m = nodes[k].first;
            p.rate_m_per_s = nodes[k].second;
            p.outer_accel_m_per_s2 = g;
            double path_d, path_r;
            contact_path_at(pair, p, H, H, path_d, path_r);
            worst = std::max(worst, std::abs(path_d - nodes[k + 1].first) / top);
        }
        std::cout << "[ path     ] e " << e << ": " << nodes.size() << " nodes, worst overlap error a step on " << worst
                  << " of the largest\n";
        EXPECT_GT(nodes.size(), 20u);
        EXPECT_LT(worst, 1e-5);
    }
}

INSTANTIATE_TEST_SUITE_P(Laws, SoftContactImpulseLaws, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) { return info.param ? "linear" : "hertz"; });

}  // namespace
}  // namespace peensim::testing
