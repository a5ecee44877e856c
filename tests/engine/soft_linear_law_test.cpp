// The second soft law, linear-spring-dashpot (contact/linear_spring_dashpot_law.h), in the soft
// scheme against its closed forms: a normal impact rebounds at e exactly at every speed (the
// damped linear oscillator from touch to separation: rebound e v, e = exp(-zeta pi / sqrt(1 -
// zeta^2))) and lasts pi / omega_d, whatever the speed; its constants as LIGGGHTS's `model hooke`.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "contact/hertz_mindlin.h"
#include "contact/linear_spring_dashpot_law.h"
#include "engine/simulation.h"
#include "support/run_through_loop.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

constexpr double kShotMass = 7800.0 * 4.0 / 3.0 * M_PI * 1e-9;  // kg, a 2 mm steel shot
const contact::ElasticMaterial kSteel{200e9, 0.3};

contact::SoftPair wall_pair(double e, double characteristic_speed) {
    return contact::linear_spring_dashpot_pair(kSteel, kSteel, 1e-3, contact::kInfinite, kShotMass, contact::kInfinite, e, 0.1,
                                               characteristic_speed, 1.0);
}

TEST(LinearSpringDashpot, ItsConstantsAreLiggghtsHookes) {
    const contact::SoftPair p = wall_pair(0.8, 2.0);
    // k_n = 16/15 sqrt(R*) E* (15 m* v^2 / (16 sqrt(R*) E*))^(1/5): R* 1 mm, E* = E / (2 (1 - nu^2)) against a wall of steel.
    const double E_star = 200e9 / (2.0 * (1.0 - 0.09)), root_r = std::sqrt(1e-3);
    const double kn = 16.0 / 15.0 * root_r * E_star * std::pow(15.0 * kShotMass * 4.0 / (16.0 * root_r * E_star), 0.2);
    EXPECT_NEAR(p.normal_stiffness_n_per_m, kn, 1e-12 * kn);
    EXPECT_EQ(p.tangential_stiffness_n_per_m, p.normal_stiffness_n_per_m);
    // The damper: LIGGGHTS's gamma_n = sqrt(4 m* k_n / (1 + (pi / ln e)^2)).
    const double gamma = std::sqrt(4.0 * kShotMass * kn / (1.0 + std::pow(M_PI / std::log(0.8), 2)));
    EXPECT_NEAR(contact::linear_normal_damping(p), gamma, 1e-12 * gamma);
    // The forces: k delta + c rate (none apart), and the spring's energy.
    EXPECT_NEAR(contact::soft_normal_force(p, 2e-6, 0.5), kn * 2e-6 + gamma * 0.5, 1e-12 * kn * 2e-6);
    EXPECT_EQ(contact::soft_normal_force(p, -1e-9, 0.5), 0.0);
    EXPECT_NEAR(contact::soft_elastic_energy(p, 2e-6), 0.5 * kn * 4e-12, 1e-12 * kn * 4e-12);
    // The greatest overlap of an elastic impact at v_c is Hertz's: v_c sqrt(m* / k_n) = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5).
    const double hertz_depth = std::pow(15.0 * kShotMass * 4.0 / (16.0 * E_star * root_r), 0.4);
    EXPECT_NEAR(2.0 * std::sqrt(kShotMass / kn), hertz_depth, 1e-12 * hertz_depth);
    // Duration pi / omega_d, the same at every speed.
    const double wd = std::sqrt(kn / kShotMass - std::pow(0.5 * gamma / kShotMass, 2));
    EXPECT_NEAR(contact::soft_contact_duration(p, 0.1), M_PI / wd, 1e-12 * M_PI / wd);
    EXPECT_EQ(contact::soft_contact_duration(p, 0.1), contact::soft_contact_duration(p, 10.0));
}

// One shot thrown at the still plate (the sonotrode, not vibrating) without gravity.
ImpactRecord one_impact(double e, double v_m_per_s, double steps_per_contact) {
    TestSceneSpec spec;
    spec.scheme = "soft";
    spec.soft = SoftSpec{};
    spec.soft->linear = true;
    spec.soft->e_sonotrode = e;
    spec.soft->steps_per_contact = steps_per_contact;
    spec.amplitude_m = 0.0;
    spec.gravity_m_per_s2 = Vec3::Zero();
    spec.chamber_size_m = Vec3(40e-3, 40e-3, 40e-3);
    spec.duration_s = 2e-3 / v_m_per_s;
    spec.log = {"sonotrode"};
    const TestScene scene(spec);
    const auto model = scene.compile();
    Simulation sim(model);
    const double R = model->max_shot_radius_m;
    sim.edit_state([&](SimulationState& s) { set_shot(s, 0, Vec3(0.0, 0.0, R + 1e-3), Vec3(0.0, 0.0, -v_m_per_s)); });
    const std::vector<ImpactRecord> impacts = run_collecting_impacts(sim);
    EXPECT_EQ(sim.state().health.serious(), 0u);
    EXPECT_EQ(impacts.size(), 1u);
    return impacts.empty() ? ImpactRecord{} : impacts.front();
}

// Measured at the default 20 steps per contact, over 0.1-20 m/s: rebound / (e approach) - 1 is
// 8.5e-11 elastic, -2.9e-5 at e 0.9 and -4.4e-4 at e 0.6 (the same at every speed from 0.5 m/s: the
// linear law has no speed scale; the damped error is the damper's jump, second order in the step,
// see below); the duration within 2.4e-6 of pi / omega_d.
TEST(LinearSpringDashpot, ANormalImpactReboundsAtEAndLastsPiOverOmegaAtEverySpeed) {
    double worst_rebound = 0.0, worst_duration = 0.0;
    for (const double e : {1.0, 0.9, 0.6})
        for (const double v : {0.1, 0.5, 2.0, 10.0, 20.0}) {
            const ImpactRecord r = one_impact(e, v, 20.0);
            const double closed = contact::soft_contact_duration(wall_pair(e, 2.0), v);
            const double rebound = r.vn_out_m_per_s / (e * r.vn_in_m_per_s) - 1.0, duration = r.duration_s / closed - 1.0;
            std::cout << "[ linear   ] e " << e << " v " << v << " m/s: rebound / (e v) - 1 " << rebound
                      << ", duration / (pi / omega_d) - 1 " << duration << "\n";
            EXPECT_NEAR(r.vn_in_m_per_s, v, 1e-9 * v);  // the exact touch's approach
            worst_rebound = std::max(worst_rebound, std::abs(rebound));
            worst_duration = std::max(worst_duration, std::abs(duration));
            EXPECT_LT(std::abs(rebound), e == 1.0 ? 1e-9 : e == 0.9 ? 4e-5 : 6e-4) << e << " " << v;
            EXPECT_LT(std::abs(duration), 1e-5) << e << " " << v;
        }
    std::cout << "[ linear   ] worst rebound error " << worst_rebound << ", duration " << worst_duration << "\n";
}

// The damped error comes from the damper's force, c times the rate, which jumps at the touch and
// at the separation (Hertz's damping vanishes there as delta^1/4): the pool's path from a node in a
// gap has no feedback of the force on the rate, so the half step that holds the separation is
// off at second order in the step. Measured rebound / (e v) - 1 at e 0.6: -4.4e-4, -1.1e-4,
// -2.8e-5 at 20, 40 and 80 steps per contact (the step's square); e 0.9: -2.9e-5 at 20.
TEST(LinearSpringDashpot, TheDampedReboundErrorFallsAsTheStepSquared) {
    double previous = 0.0;
    for (const double steps : {20.0, 40.0, 80.0}) {
        const ImpactRecord r = one_impact(0.6, 2.0, steps);
        const double err = r.vn_out_m_per_s / (0.6 * r.vn_in_m_per_s) - 1.0;
        std::cout << "[ linear   ] e 0.6, " << steps << " steps per contact: rebound / (e v) - 1 " << err << "\n";
        if (previous != 0.0) {
            EXPECT_NEAR(previous / err, 4.0, 0.4) << steps;  // second order
        }
        previous = err;
    }
}

// A soft law is a law: the same scene with hertz-mindlin and with linear-spring-dashpot runs in the
// soft scheme and the laws differ where they should (Hertz's contact shortens with speed, the
// linear one's does not).
TEST(LinearSpringDashpot, HertzContactsShortenWithSpeedTheLinearOnesDoNot) {
    const ImpactRecord slow = one_impact(0.9, 0.5, 20.0), fast = one_impact(0.9, 10.0, 20.0);
    EXPECT_NEAR(fast.duration_s / slow.duration_s, 1.0, 0.05);
    const contact::SoftPair hertz = contact::hertz_pair(kSteel, kSteel, 1e-3, contact::kInfinite, kShotMass, contact::kInfinite, 0.9, 0.1);
    EXPECT_NEAR(contact::hertz_contact_duration(hertz, 10.0) / contact::hertz_contact_duration(hertz, 0.5), std::pow(20.0, -0.2), 1e-12);
}

}  // namespace
}  // namespace peensim::testing
