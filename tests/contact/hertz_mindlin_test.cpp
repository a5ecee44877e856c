// The soft-sphere contact functions (contact/hertz_mindlin.h): exact values of the pair constants,
// damping and forces; a normal impact on a wall integrated at a fixed fraction of the Hertz time
// rebounds at e v (the damping form's restitution is e at every speed) and lasts the Hertz time
// when elastic; the tangential spring sticks below Coulomb's cap and slides at it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "contact/hertz_mindlin.h"

namespace peensim::contact {
namespace {

const ElasticMaterial kSteelElastic{200e9, 0.3};
constexpr double kShotR = 1e-3;  // m, a 2 mm shot
const double kShotMass = 7800.0 * 4.0 / 3.0 * M_PI * kShotR * kShotR * kShotR;

TEST(HertzMindlin, PairConstantsAreTheReferencesFormulas) {
    const SoftPair wall = hertz_pair(kSteelElastic, kSteelElastic, kShotR, kInfinite, kShotMass, kInfinite, 0.9, 0.1);
    EXPECT_DOUBLE_EQ(wall.E_star_pa, 200e9 / (2.0 * 0.91));
    EXPECT_DOUBLE_EQ(wall.G_star_pa, 200e9 / (4.0 * 1.7 * 1.3));
    EXPECT_EQ(wall.R_star_m, kShotR);
    EXPECT_EQ(wall.m_star_kg, kShotMass);
    EXPECT_DOUBLE_EQ(wall.beta, std::log(0.9) / std::sqrt(std::log(0.9) * std::log(0.9) + M_PI * M_PI));
    EXPECT_EQ(wall.friction, 0.1);
    const SoftPair shots = hertz_pair(kSteelElastic, kSteelElastic, kShotR, kShotR, kShotMass, kShotMass, 1.0, 0.1);
    EXPECT_DOUBLE_EQ(shots.R_star_m, 0.5 * kShotR);
    EXPECT_DOUBLE_EQ(shots.m_star_kg, 0.5 * kShotMass);
    EXPECT_EQ(shots.beta, 0.0);  // e = 1: no damping
}

TEST(HertzMindlin, NormalForceIsHertzPlusDamping) {
    const SoftPair p = hertz_pair(kSteelElastic, kSteelElastic, kShotR, kInfinite, kShotMass, kInfinite, 0.9, 0.1);
    const double d = 1e-6, rate = 2.0;  // m, m/s
    const double elastic = 4.0 / 3.0 * p.E_star_pa * std::sqrt(kShotR) * std::pow(d, 1.5);
    const double damping = -2.0 * std::sqrt(5.0 / 6.0) * p.beta * std::sqrt(2.0 * p.E_star_pa * std::sqrt(kShotR * d) * kShotMass) * rate;
    EXPECT_NEAR(hertz_normal_force(p, d, rate), elastic + damping, 1e-12 * (elastic + damping));
    EXPECT_GT(damping, 0.0);  // resists the approach
    EXPECT_EQ(hertz_normal_force(p, 0.0, 0.0), 0.0);
    EXPECT_LT(hertz_normal_force(p, d, -rate), elastic);  // and the separation
    // Its two coefficients give the same force (the soft scheme integrates it through them).
    const HertzCoefficients c = hertz_coefficients(p);
    for (const double delta : {1e-9, 1e-7, 1e-5})
        for (const double r : {-3.0, 0.0, 0.5})
            EXPECT_NEAR(c.elastic * std::pow(delta, 1.5) + c.damping * std::pow(delta, 0.25) * r, hertz_normal_force(p, delta, r),
                        1e-12 * std::abs(hertz_normal_force(p, delta, 3.0)));
    EXPECT_GT(c.damping, 0.0);
    EXPECT_EQ(hertz_coefficients(hertz_pair(kSteelElastic, kSteelElastic, kShotR, kInfinite, kShotMass, kInfinite, 1.0, 0.1)).damping, 0.0);
}

struct Rebound {
    double restitution;  // -, rebound speed over approach speed
    double duration_s;   // s
};

// A normal impact on a wall at v (m/s): the overlap's equation m* d'' = -F(d, d') by classical
// Runge-Kutta at `per_contact` steps per Hertz time, until the overlap is zero again.
Rebound normal_impact(const SoftPair& p, double v, int per_contact) {
    const double dt = hertz_contact_duration(p, v) / per_contact;
    const auto acc = [&](double d, double r) { return -hertz_normal_force(p, d, r) / p.m_star_kg; };
    double d = 0.0, r = v, t = 0.0;
    for (int k = 0; k < 100 * per_contact; ++k) {
        const double k1d = r, k1r = acc(d, r);
        const double k2d = r + 0.5 * dt * k1r, k2r = acc(d + 0.5 * dt * k1d, r + 0.5 * dt * k1r);
        const double k3d = r + 0.5 * dt * k2r, k3r = acc(d + 0.5 * dt * k2d, r + 0.5 * dt * k2r);
        const double k4d = r + dt * k3r, k4r = acc(d + dt * k3d, r + dt * k3r);
        const double d1 = d + dt / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d), r1 = r + dt / 6.0 * (k1r + 2.0 * k2r + 2.0 * k3r + k4r);
        if (d1 <= 0.0 && t > 0.0) {
            const double f = d / (d - d1);  // the step's fraction to the separation (linear)
            return {-(r + f * (r1 - r)) / v, t + f * dt};
        }
        d = d1, r = r1, t += dt;
    }
    return {NAN, NAN};
}

TEST(HertzMindlin, ANormalImpactReboundsAtEAtEverySpeedAndLastsTheHertzTime) {
    for (double e : {0.9, 0.7, 0.5})
        for (double v : {0.5, 2.0, 10.0}) {
            const SoftPair p = hertz_pair(kSteelElastic, kSteelElastic, kShotR, kInfinite, kShotMass, kInfinite, e, 0.1);
            // Measured at 200 steps per Hertz time: within 5e-4 of e (0.90004, 0.70018, 0.50026 at
            // every speed); converged (2000 steps) 0.90000, 0.50002.
            EXPECT_NEAR(normal_impact(p, v, 200).restitution, e, 0.005 * e) << "e " << e << ", v " << v;
        }
    const SoftPair elastic = hertz_pair(kSteelElastic, kSteelElastic, kShotR, kInfinite, kShotMass, kInfinite, 1.0, 0.1);
    for (double v : {0.5, 2.0, 10.0}) {
        const Rebound r = normal_impact(elastic, v, 200);
        EXPECT_NEAR(r.restitution, 1.0, 1e-5);  // measured: 1.14e-6 short (the last step's linear crossing)
        // 2.87 is the rounded constant: measured 0.9994 of it.
        EXPECT_NEAR(r.duration_s, hertz_contact_duration(elastic, v), 0.01 * hertz_contact_duration(elastic, v));
    }
    // 2 mm steel on steel at 2 m/s: 6.1 us, a thirtieth of a 20 kHz period.
    EXPECT_NEAR(hertz_contact_duration(elastic, 2.0), 6.12e-6, 0.01e-6);
}

TEST(HertzMindlin, TheTangentialSpringSticksBelowCoulombsCapAndSlidesAtIt) {
    const SoftPair p =
        hertz_pair(kSteelElastic, kSteelElastic, kShotR, kInfinite, kShotMass, kInfinite, 1.0, 0.1);  // no damping: the spring alone
    const double d = 1e-6, fn = hertz_normal_force(p, d, 0.0);
    const double s_t = 8.0 * p.G_star_pa * std::sqrt(kShotR * d);
    Vec3 spring = Vec3::Zero();
    // A small slip: stuck, the force the spring's.
    const Vec3 f1 = mindlin_tangential_force(p, d, fn, Vec3(1e-3, 0, 0), 1e-6, spring);
    EXPECT_DOUBLE_EQ(spring.x(), 1e-9);
    EXPECT_DOUBLE_EQ(f1.x(), -s_t * 1e-9);
    EXPECT_LT(f1.norm(), p.friction * fn);
    // A long slip: sliding at the cap, the spring shortened to what the cap holds.
    const Vec3 f2 = mindlin_tangential_force(p, d, fn, Vec3(0, 1.0, 0), 1e-6, spring);
    EXPECT_NEAR(f2.norm(), p.friction * fn, 1e-12 * fn);
    EXPECT_NEAR((-s_t * spring - f2).norm(), 0.0, 1e-9 * fn);
    EXPECT_LT(f2.y(), 0.0);  // against the slip
}

// LIGGGHTS 3.8's `tangential history` (its src/tangential_model_history.h), written out for the
// comparison of tests/bench/soft_vs_liggghts (docs/design.md, "Soft-sphere contacts"): the same spring and
// damping, but its Coulomb cap compares the spring's force alone with f |F_n| (the magnitude of the
// damped normal force, which pulls at the end of a damped contact) and drops the damping while
// sliding; mindlin_tangential_force caps the spring and its damping together at f max(0, F_n).
Vec3 liggghts_tangential_force(const SoftPair& p, double delta_m, double normal_force_n, const Vec3& v_t, double dt_s, Vec3& shear_m) {
    const double s_t = 8.0 * p.G_star_pa * std::sqrt(p.R_star_m * std::max(0.0, delta_m));
    shear_m += v_t * dt_s;
    Vec3 force = -s_t * shear_m;
    const double cap = p.friction * std::abs(normal_force_n);
    if (force.norm() > cap) {
        force *= cap / force.norm();
        shear_m = -force / s_t;
        return force;
    }
    return force + 2.0 * std::sqrt(5.0 / 6.0) * p.beta * std::sqrt(s_t * p.m_star_kg) * v_t;  // beta < 0: opposes v_t
}

TEST(HertzMindlin, CoulombsCapTakesTheSpringWithItsDampingAndNoPullUnlikeLiggghts) {
    const SoftPair p = hertz_pair(kSteelElastic, kSteelElastic, kShotR, kInfinite, kShotMass, kInfinite, 0.8, 0.3);
    const double d = 1e-6, s_t = 8.0 * p.G_star_pa * std::sqrt(kShotR * d);
    const double gamma_t = -2.0 * std::sqrt(5.0 / 6.0) * p.beta * std::sqrt(s_t * kShotMass);  // N s/m, > 0
    const double fn = hertz_normal_force(p, d, 0.0), cap = p.friction * fn;
    // The spring's force at 0.9 of the cap and its damping's 0.3 of it. Opposed, both laws give
    // their sum, 0.6 of the cap.
    const Vec3 v_t(0.3 * cap / gamma_t, 0.0, 0.0);
    Vec3 spring(-0.9 * cap / s_t, 0.0, 0.0), shear = spring;
    EXPECT_NEAR(mindlin_tangential_force(p, d, fn, v_t, Vec3::Zero(), spring).x(), 0.6 * cap, 1e-12 * cap);
    EXPECT_NEAR(liggghts_tangential_force(p, d, fn, v_t, 0.0, shear).x(), 0.6 * cap, 1e-12 * cap);
    // Together (the spring loading while the contact point still slips): LIGGGHTS holds 1.2 times
    // Coulomb's cap (its spring alone is below it); this law slides at the cap.
    spring = shear = Vec3(0.9 * cap / s_t, 0.0, 0.0);
    EXPECT_NEAR(mindlin_tangential_force(p, d, fn, v_t, Vec3::Zero(), spring).x(), -cap, 1e-12 * cap);
    EXPECT_NEAR(liggghts_tangential_force(p, d, fn, v_t, 0.0, shear).x(), -1.2 * cap, 1e-12 * cap);
    // At the end of a damped contact the normal force pulls (F_n < 0): no friction here, f |F_n| there.
    const double pull = hertz_normal_force(p, d, -5.0);
    ASSERT_LT(pull, 0.0);
    spring = shear = Vec3(10.0 * cap / s_t, 0.0, 0.0);  // far past either cap: sliding
    EXPECT_EQ(mindlin_tangential_force(p, d, pull, Vec3::Zero(), Vec3::Zero(), spring).norm(), 0.0);
    EXPECT_NEAR(liggghts_tangential_force(p, d, pull, Vec3::Zero(), 0.0, shear).norm(), p.friction * -pull, 1e-12 * cap);
}

// A sliding impact on a wall (2 m/s normal, 8 m/s tangential, no spin; e 0.8, f 0.3), integrated as
// LIGGGHTS's nve/sphere does (half kick, drift, forces, half kick) at 1.5e-9 s (4000 steps per
// contact), with either cap. Returns the tangential speed lost over Coulomb's f (1 + e) v_n.
template <class Tangential>
double sliding_loss_over_coulomb(const SoftPair& p, Tangential tangential) {
    const double vn0 = 2.0, vt0 = 8.0, dt = 1.5e-9, inertia = 0.4 * kShotMass * kShotR * kShotR;
    double z = kShotR, vz = -vn0, vx = vt0, w = 0.0, fn = 0.0, ft = 0.0;  // the centre's height, m; spin about y, rad/s
    Vec3 spring = Vec3::Zero();
    for (int k = 0; k < 100000; ++k) {
        vz += 0.5 * dt * fn / kShotMass, vx += 0.5 * dt * ft / kShotMass, w -= 0.5 * dt * kShotR * ft / inertia;
        z += vz * dt;
        const double d = kShotR - z;
        if (d <= 0.0 && k > 0) return (vt0 - vx) / (p.friction * 1.8 * vn0);
        fn = hertz_normal_force(p, d, -vz);
        ft = tangential(d, fn, Vec3(vx - kShotR * w, 0.0, 0.0), dt, spring).x();  // the contact point's slip: v - w R
        vz += 0.5 * dt * fn / kShotMass, vx += 0.5 * dt * ft / kShotMass, w -= 0.5 * dt * kShotR * ft / inertia;
    }
    return NAN;
}

TEST(HertzMindlin, ASlidingImpactLosesCoulombsImpulseWhereLiggghtsLosesTwoPercentMore) {
    const SoftPair p = hertz_pair(kSteelElastic, kSteelElastic, kShotR, kInfinite, kShotMass, kInfinite, 0.8, 0.3);
    const double ours = sliding_loss_over_coulomb(
        p, [&](double d, double fn, const Vec3& v, double dt, Vec3& s) { return mindlin_tangential_force(p, d, fn, v, dt, s); });
    const double theirs = sliding_loss_over_coulomb(
        p, [&](double d, double fn, const Vec3& v, double dt, Vec3& s) { return liggghts_tangential_force(p, d, fn, v, dt, s); });
    std::printf("[ sliding  ] tangential loss / Coulomb's: this law %.5f, LIGGGHTS's cap %.5f\n", ours, theirs);
    // Measured: 0.99250 and 1.01906. LIGGGHTS 3.8 itself, the same impact
    // (tests/bench/soft_vs_liggghts/liggghts_single_impact.py --vn 2 --vt 8): 1.01902.
    EXPECT_NEAR(ours, 0.9925, 0.0002);
    EXPECT_NEAR(theirs, 1.0190, 0.0002);
}

}  // namespace
}  // namespace peensim::contact
