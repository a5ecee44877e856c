// The contact laws of contact/ against hand-computed values (reference eq. 2-5): restitution in
// both regimes, shot-shot impulses, static and moving surface impacts, sustained-contact friction,
// (the law catalogue and the stateful laws: tests/contact/law_catalogue_test.cpp).
//
// Tolerances: the hand values below are chosen so that the laws' arithmetic is exact or a few
// roundings away from it; 1e-15 m/s (a few ulp of speeds of order 1 m/s) is the bound used
// unless a value is exact (EXPECT_EQ).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "contact/impulse_laws.h"
#include "contact/law_registry.h"
#include "contact/restitution.h"

namespace peensim::contact {
namespace {

constexpr double kUlpSpeed = 1e-15;  // m/s, a few roundings of speeds of order 1 m/s

void expect_vec_near(const Vec3& actual, const Vec3& expected, double tolerance, const std::string& what) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(actual[k], expected[k], tolerance) << what << ", component " << k;
}

TEST(ContactRestitution, ElasticBelowV0) {
    EXPECT_EQ(normal_restitution(0.0, 0.9, 0.5), 0.9);
    EXPECT_EQ(normal_restitution(0.3, 0.9, 0.5), 0.9);
    EXPECT_EQ(normal_restitution(0.4999999, 0.9, 0.5), 0.9);
}

TEST(ContactRestitution, PlasticFromV0On) {
    // At V0, (V/V0)^-1/4 = 1; V = 16 V0 gives 16^-1/4 = 1/2 exactly (two exact square roots).
    EXPECT_EQ(normal_restitution(0.5, 0.9, 0.5), 0.9);
    EXPECT_EQ(normal_restitution(8.0, 0.9, 0.5), 0.45);
    EXPECT_EQ(normal_restitution(8.0, 0.9, 0.5), 0.9 / 2.0);
    // 81 V0: 81^-1/4 = 1/3 (0.9 / 3 rounds once).
    EXPECT_DOUBLE_EQ(normal_restitution(40.5, 0.9, 0.5), 0.3);
    // A generic speed against the formula written directly with pow.
    EXPECT_NEAR(normal_restitution(3.7, 0.95, 2.0), 0.95 * std::pow(3.7 / 2.0, -0.25), 1e-15);
    // Continuous at V0 and decreasing above it.
    EXPECT_LT(normal_restitution(0.51, 0.9, 0.5), 0.9);
    EXPECT_GT(normal_restitution(0.51, 0.9, 0.5), normal_restitution(0.52, 0.9, 0.5));
}

TEST(ContactShotShot, HeadOnElastic) {
    // dV = (v_j - v_i).n = -3; C = 0.5 (V0 10 m/s: elastic): impulse/m = 0.5 (1.5) (-3) n = -2.25 n.
    const ShotShotResponse r =
        ImpulseShotShotLaw(PairCoefficients{0.5, 10.0, 0.0, 0.0}).respond({Vec3(2, 0, 0), Vec3(-1, 0, 0), Vec3(1, 0, 0)});
    EXPECT_TRUE(r.approaching);
    EXPECT_EQ(r.vn_in, 3.0);
    EXPECT_EQ(r.v_i, Vec3(-0.25, 0, 0));
    EXPECT_EQ(r.v_j, Vec3(1.25, 0, 0));
}

TEST(ContactShotShot, HeadOnPlastic) {
    // dV = -8 = 16 V0: C = 0.45; impulse/m = 0.5 (1.45) (-8) = -5.8.
    const ShotShotResponse r =
        ImpulseShotShotLaw(PairCoefficients{0.9, 0.5, 0.0, 0.0}).respond({Vec3(4, 0, 0), Vec3(-4, 0, 0), Vec3(1, 0, 0)});
    EXPECT_EQ(r.vn_in, 8.0);
    expect_vec_near(r.v_i, Vec3(-1.8, 0, 0), kUlpSpeed, "v_i");
    expect_vec_near(r.v_j, Vec3(1.8, 0, 0), kUlpSpeed, "v_j");
}

TEST(ContactShotShot, Oblique) {
    // n = (0.6, 0.8, 0); v_i = (1, 0, 0.5), v_j = (0, -1, 0.25): dV = -0.6 - 0.8 = -1.4.
    // C = 1: impulse/m = -1.4 n = (-0.84, -1.12, 0). Tangential parts (z here) unchanged.
    const ShotShotResponse r =
        ImpulseShotShotLaw(PairCoefficients{1.0, 100.0, 0.0, 0.0}).respond({Vec3(1, 0, 0.5), Vec3(0, -1, 0.25), Vec3(0.6, 0.8, 0)});
    EXPECT_NEAR(r.vn_in, 1.4, kUlpSpeed);
    expect_vec_near(r.v_i, Vec3(0.16, -1.12, 0.5), kUlpSpeed, "v_i");
    expect_vec_near(r.v_j, Vec3(0.84, 0.12, 0.25), kUlpSpeed, "v_j");
    EXPECT_EQ(r.v_i.z(), 0.5);
    EXPECT_EQ(r.v_j.z(), 0.25);
}

TEST(ContactShotShot, MomentumConservedToRoundOff) {
    // Random pairs in both regimes: the sum of velocities is unchanged to a few roundings of the
    // largest velocity involved (|error| <= ~4 ulp; asserted 1e-15 relative).
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-10.0, 10.0);
    int approaching = 0;
    for (int k = 0; k < 10000; ++k) {
        const Vec3 vi(u(rng), u(rng), u(rng)), vj(u(rng), u(rng), u(rng));
        const Vec3 n = Vec3(u(rng), u(rng), u(rng)).normalized();
        const ShotShotResponse r = ImpulseShotShotLaw(PairCoefficients{0.9, 0.5, 0.0, 0.0}).respond({vi, vj, n});
        const double scale = std::max({vi.norm(), vj.norm(), r.v_i.norm(), r.v_j.norm()});
        EXPECT_LE(((r.v_i + r.v_j) - (vi + vj)).norm(), 1e-15 * scale) << "case " << k;
        approaching += r.approaching;
        if (r.approaching) {
            // Only the normal component changed.
            EXPECT_NEAR(((r.v_i - vi) - (r.v_i - vi).dot(n) * n).norm(), 0.0, 1e-14 * scale) << "case " << k;
            // Post-impact relative normal speed is C times the approach speed.
            const double C = normal_restitution(r.vn_in, 0.9, 0.5);
            EXPECT_NEAR((r.v_j - r.v_i).dot(n), C * r.vn_in, 1e-14 * scale) << "case " << k;
        }
    }
    EXPECT_GT(approaching, 4000);  // about half the random pairs approach
}

TEST(ContactShotShot, UnequalMassesHeadOnExact) {
    // A shot mix: m_i = 1, m_j = 3 (mass units); dV = -4, C = 0.5 (elastic regime): the exchange is
    // (1 + C) dV = -6; i takes 3/4 of it, j 1/4: v_i = 2 - 4.5 = -2.5, v_j = -2 + 1.5 = -0.5 (exact).
    ShotShotInput in{Vec3(2, 0, 0), Vec3(-2, 0, 0), Vec3(1, 0, 0)};
    in.mass_i_kg = 1.0;
    in.mass_j_kg = 3.0;
    const ShotShotResponse r = ImpulseShotShotLaw(PairCoefficients{0.5, 10.0, 0.0, 0.0}).respond(in);
    EXPECT_EQ(r.vn_in, 4.0);
    EXPECT_EQ(r.v_i, Vec3(-2.5, 0, 0));
    EXPECT_EQ(r.v_j, Vec3(-0.5, 0, 0));
    // Momentum m_i v_i + m_j v_j = 2 - 6 = -4 before and -2.5 - 1.5 = -4 after; separation C dV.
    EXPECT_EQ(1.0 * r.v_i.x() + 3.0 * r.v_j.x(), -4.0);
    EXPECT_EQ(r.v_j.x() - r.v_i.x(), 2.0);
    // Equal masses given explicitly: exactly the shares of masses left out (a half each).
    in.mass_j_kg = 1.0;
    const ShotShotResponse equal = ImpulseShotShotLaw(PairCoefficients{0.5, 10.0, 0.0, 0.0}).respond(in);
    in.mass_i_kg = in.mass_j_kg = 0.0;
    const ShotShotResponse unweighed = ImpulseShotShotLaw(PairCoefficients{0.5, 10.0, 0.0, 0.0}).respond(in);
    EXPECT_EQ(equal.v_i, unweighed.v_i);
    EXPECT_EQ(equal.v_j, unweighed.v_j);
    EXPECT_EQ(equal.v_i, Vec3(-1, 0, 0));
}

TEST(ContactShotShot, UnequalMassesConserveMomentumAndRestitution) {
    // Random pairs of a 0.425 and a 0.71 mm shot (mass ratio 4.66) in both regimes: mass-weighted
    // momentum kept to round-off, the relative normal speed reversed by C, tangential parts kept.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-10.0, 10.0);
    const double mi = 0.425 * 0.425 * 0.425, mj = 0.71 * 0.71 * 0.71;
    for (int k = 0; k < 10000; ++k) {
        ShotShotInput in{Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)).normalized()};
        const bool swap = k % 2 == 1;  // either order
        in.mass_i_kg = swap ? mj : mi;
        in.mass_j_kg = swap ? mi : mj;
        const ShotShotResponse r = ImpulseShotShotLaw(PairCoefficients{0.9, 0.5, 0.0, 0.0}).respond(in);
        const double scale = (in.mass_i_kg + in.mass_j_kg) * std::max({in.v_i.norm(), in.v_j.norm(), r.v_i.norm(), r.v_j.norm()});
        EXPECT_LE(((in.mass_i_kg * r.v_i + in.mass_j_kg * r.v_j) - (in.mass_i_kg * in.v_i + in.mass_j_kg * in.v_j)).norm(), 1e-14 * scale)
            << "case " << k;
        if (!r.approaching) continue;
        EXPECT_NEAR((r.v_j - r.v_i).dot(in.normal), normal_restitution(r.vn_in, 0.9, 0.5) * r.vn_in, 1e-13 * scale) << "case " << k;
        // The light shot's velocity changes mj / mi times as much as the heavy one's.
        const double light = ((swap ? r.v_j - in.v_j : r.v_i - in.v_i)).norm(), heavy = ((swap ? r.v_i - in.v_i : r.v_j - in.v_j)).norm();
        EXPECT_NEAR(light, heavy * mj / mi, 1e-12 * scale) << "case " << k;
    }
}

TEST(ContactShotShot, SeparatingPairUnchanged) {
    const Vec3 vi(-1, 0.3, 0), vj(2, 0, 1);
    const ShotShotResponse r = ImpulseShotShotLaw(PairCoefficients{0.9, 0.5, 0.0, 0.0}).respond({vi, vj, Vec3(1, 0, 0)});
    EXPECT_FALSE(r.approaching);
    EXPECT_EQ(r.v_i, vi);
    EXPECT_EQ(r.v_j, vj);
    EXPECT_EQ(r.vn_in, 0.0);
    // Grazing (dV . n == 0) is not an approach either.
    const ShotShotResponse g =
        ImpulseShotShotLaw(PairCoefficients{0.9, 0.5, 0.0, 0.0}).respond({Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(1, 0, 0)});
    EXPECT_FALSE(g.approaching);
}

TEST(ContactSurfaceImpact, StaticEq4Elastic) {
    // V = (1, 0, -2), n = +z, mu 0.5, C = 0.8 (V0 5 m/s): V' = (0.5, 0, 1.6).
    const SurfaceContactResponse r =
        ImpulseSurfaceLaw(PairCoefficients{0.8, 5.0, 0.5, 0.1}).impact({Vec3(1, 0, -2), Vec3::Zero(), Vec3::UnitZ(), 0.0, 1e-4}, {});
    EXPECT_TRUE(r.approaching);
    EXPECT_EQ(r.v_shot, Vec3(0.5, 0, 1.6));
    EXPECT_EQ(r.vn_in, 2.0);
    EXPECT_EQ(r.vt_in, 1.0);
    EXPECT_EQ(r.vn_out, 1.6);
}

TEST(ContactSurfaceImpact, StaticEq4Plastic) {
    // V = (0, 3, -8): vn 8 = 16 V0 -> C = 0.45; mu 0.5: V' = (0, 1.5, 3.6).
    const SurfaceContactResponse r =
        ImpulseSurfaceLaw(PairCoefficients{0.9, 0.5, 0.5, 0.1}).impact({Vec3(0, 3, -8), Vec3::Zero(), Vec3::UnitZ(), 0.0, 1e-4}, {});
    expect_vec_near(r.v_shot, Vec3(0, 1.5, 3.6), kUlpSpeed, "v'");
    EXPECT_EQ(r.vn_in, 8.0);
    EXPECT_EQ(r.vt_in, 3.0);
    EXPECT_NEAR(r.vn_out, 3.6, kUlpSpeed);
}

TEST(ContactSurfaceImpact, StaticEq4TiltedNormal) {
    // n = (0, 0.6, 0.8), V = (0, 0, -5): V.n = -4, normal part (0, -2.4, -3.2), tangential
    // (0, 2.4, -1.8); mu 0.5, C 0.5: V' = (0, 1.2, -0.9) + 2 (0, 0.6, 0.8) = (0, 2.4, 0.7).
    const SurfaceContactResponse r =
        ImpulseSurfaceLaw(PairCoefficients{0.5, 100.0, 0.5, 0.1}).impact({Vec3(0, 0, -5), Vec3::Zero(), Vec3(0, 0.6, 0.8), 0.0, 1e-4}, {});
    expect_vec_near(r.v_shot, Vec3(0, 2.4, 0.7), 4 * kUlpSpeed, "v'");
    EXPECT_NEAR(r.vn_in, 4.0, kUlpSpeed);
    EXPECT_NEAR(r.vt_in, 3.0, kUlpSpeed);
}

TEST(ContactSurfaceImpact, MovingSurfaceEq5) {
    // Sonotrode moving up at 2 m/s, V = (1, 0, -6): dV = (1, 0, -8), 16 V0 -> C = 0.45,
    // mu 0.71: V' = (0, 0, 2) + 0.71 (1, 0, 0) + 0.45 * 8 (0, 0, 1) = (0.71, 0, 5.6).
    const SurfaceContactResponse r =
        ImpulseSurfaceLaw(PairCoefficients{0.9, 0.5, 0.71, 0.1}).impact({Vec3(1, 0, -6), Vec3(0, 0, 2), Vec3::UnitZ(), 0.0, 1e-4}, {});
    EXPECT_TRUE(r.approaching);
    expect_vec_near(r.v_shot, Vec3(0.71, 0, 5.6), kUlpSpeed, "v'");
    EXPECT_EQ(r.vn_in, 8.0);
    EXPECT_EQ(r.vt_in, 1.0);
    EXPECT_NEAR(r.vn_out, 3.6, kUlpSpeed);

    // A surface moving along itself (a rotating part's rim): V = (0, 0, -1), V_s = (0.5, 0.2, 0),
    // dV_t = (-0.5, -0.2, 0); mu 0.8, C 0.9: V' = V_s + 0.8 dV_t + 0.9 (0, 0, 1) = (0.1, 0.04, 0.9).
    const SurfaceContactResponse s =
        ImpulseSurfaceLaw(PairCoefficients{0.9, 10.0, 0.8, 0.1}).impact({Vec3(0, 0, -1), Vec3(0.5, 0.2, 0), Vec3::UnitZ(), 0.0, 1e-4}, {});
    expect_vec_near(s.v_shot, Vec3(0.1, 0.04, 0.9), kUlpSpeed, "v' (tangential surface motion)");
    EXPECT_NEAR(s.vt_in, std::sqrt(0.29), kUlpSpeed);
    EXPECT_EQ(s.vn_in, 1.0);
}

TEST(ContactSurfaceImpact, SeparatingUnchanged) {
    const PairCoefficients k{0.9, 0.5, 0.71, 0.1};
    // Moving away from a still surface.
    const SurfaceContactResponse a =
        ImpulseSurfaceLaw(PairCoefficients(k)).impact({Vec3(1, 0, 2), Vec3::Zero(), Vec3::UnitZ(), 0.0, 1e-4}, {});
    EXPECT_FALSE(a.approaching);
    EXPECT_EQ(a.v_shot, Vec3(1, 0, 2));
    EXPECT_EQ(a.vn_out, 0.0);
    // Falling, but the surface falls faster (the sonotrode's downstroke): separating.
    const SurfaceContactResponse b =
        ImpulseSurfaceLaw(PairCoefficients(k)).impact({Vec3(0, 0, -1), Vec3(0, 0, -2), Vec3::UnitZ(), 0.0, 1e-4}, {});
    EXPECT_FALSE(b.approaching);
    EXPECT_EQ(b.v_shot, Vec3(0, 0, -1));
}

TEST(ContactSurfaceSustain, ApproachStoppedAndCoulombSlowdown) {
    // Sliding at 0.5 m/s along (0.6, 0.8, 0), pressed by g = 9.81 m/s2 for dt = 0.01 s, f = 0.1:
    // the tangential speed drops by f g dt = 0.00981 m/s exactly in its own direction; the
    // approach (-0.1 m/s) is removed.
    const SurfaceContactResponse r = ImpulseSurfaceLaw(PairCoefficients{0.9, 0.5, 0.71, 0.1})
                                         .sustain({Vec3(0.3, 0.4, -0.1), Vec3::Zero(), Vec3::UnitZ(), 9.81, 0.01}, {});
    const double vt = 0.5 - 0.1 * 9.81 * 0.01;
    expect_vec_near(r.v_shot, Vec3(0.6 * vt, 0.8 * vt, 0.0), kUlpSpeed, "v'");
    EXPECT_EQ(r.v_shot.z(), 0.0);
    EXPECT_NEAR(r.v_shot.norm(), vt, kUlpSpeed);
    EXPECT_TRUE(r.approaching);
    EXPECT_NEAR(r.vn_in, 0.1, kUlpSpeed);
    EXPECT_EQ(r.vn_out, 0.0);
}

TEST(ContactSurfaceSustain, FrictionNeverReverses) {
    // 0.005 m/s of sliding against a possible slowdown of 0.00981 m/s: it stops, it does not turn back.
    const SurfaceContactResponse r =
        ImpulseSurfaceLaw(PairCoefficients{0.9, 0.5, 0.71, 0.1}).sustain({Vec3(0.005, 0, 0), Vec3::Zero(), Vec3::UnitZ(), 9.81, 0.01}, {});
    EXPECT_EQ(r.v_shot, Vec3::Zero());
}

TEST(ContactSurfaceSustain, SeparationKeptNoPullNoFrictionWithoutPressing) {
    const PairCoefficients k{0.9, 0.5, 0.71, 0.1};
    // Leaving the surface at 0.2 m/s: kept.
    const SurfaceContactResponse a =
        ImpulseSurfaceLaw(PairCoefficients(k)).sustain({Vec3(0.1, 0, 0.2), Vec3::Zero(), Vec3::UnitZ(), 9.81, 0.01}, {});
    EXPECT_EQ(a.v_shot.z(), 0.2);
    EXPECT_FALSE(a.approaching);
    // A negative pressing acceleration (the surface pulling away faster than g) gives no friction.
    const SurfaceContactResponse b =
        ImpulseSurfaceLaw(PairCoefficients(k)).sustain({Vec3(0.1, 0, 0), Vec3::Zero(), Vec3::UnitZ(), -5.0, 0.01}, {});
    EXPECT_EQ(b.v_shot, Vec3(0.1, 0, 0));
}

TEST(ContactSurfaceSustain, MovingSurface) {
    // The surface rises at 1 m/s, the shot at 0.5 m/s with 0.1 m/s sideways: relative (0.1, 0, -0.5).
    // The approach is stopped (shot rides at the surface's 1 m/s) and friction f a dt = 0.1 * 20 * 0.01
    // = 0.02 m/s is taken off the relative sliding speed.
    const SurfaceContactResponse r =
        ImpulseSurfaceLaw(PairCoefficients{0.9, 0.5, 0.71, 0.1}).sustain({Vec3(0.1, 0, 0.5), Vec3(0, 0, 1), Vec3::UnitZ(), 20.0, 0.01}, {});
    expect_vec_near(r.v_shot, Vec3(0.08, 0, 1.0), kUlpSpeed, "v'");
}

TEST(ContactImpactRule, ApproachSpeedAgainstTheImpactSpeed) {
    EXPECT_TRUE(is_impact(0.2, 0.1));
    EXPECT_TRUE(is_impact(0.1, 0.1));  // at the threshold: an impact; slower: sustained contact
    EXPECT_FALSE(is_impact(0.1 * (1.0 - 1e-15), 0.1));
    EXPECT_FALSE(is_impact(0.0, 0.05));
}

}  // namespace
}  // namespace peensim::contact
