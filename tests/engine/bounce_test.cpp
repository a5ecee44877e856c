// One shot dropped from rest onto the still sonotrode: impact times, impact and rebound speeds
// against the closed form of a bouncing ball with constant restitution C (V0 far above every speed):
//   first impact at t1 = sqrt(2 h0 / g) with speed v1 = sqrt(2 g h0);
//   impact k (from 1) at speed C^(k-1) v1, rebound C^k v1, apex C^(2k) h0 above the contact height;
//   t(k+1) = t(k) + 2 C^k v1 / g.
// The engine finds the exact touch time of a shot's parabola with a plane (a quadratic), so the
// only errors are roundings: asserted below 1e-9 relative at every travel fraction (measured:
// ~1e-15, see the printout), and not growing as the step shrinks (up to a round-off floor).
// The event-driven scheme (accuracy.scheme: event) flies the same parabola to the same plane: its
// first 8 bounces are asserted to the same 1e-9 relative.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "engine/simulation.h"
#include "support/run_through_loop.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

constexpr double kG = 9.81;    // m/s2
constexpr double kH0 = 10e-3;  // m, drop height of the centre above its height at contact
constexpr double kC = 0.8;     // -, shot-sonotrode restitution (V0 1000 m/s: always elastic regime)
constexpr int kImpactsChecked = 8;

struct DropErrors {
    double time = 0.0;      // largest relative error of an impact time
    double speed_in = 0.0;  // ... of an impact speed
    double apex = 0.0;      // ... of an apex height (from the rebound speed)
    int impacts = 0;
};

DropErrors drop(double travel_fraction, const std::string& scheme = "step") {
    TestSceneSpec spec;
    spec.chamber_size_m = Vec3(20e-3, 20e-3, 30e-3);
    spec.amplitude_m = 0.0;
    spec.sonotrode = {kC, 1e3, 0.71, 0.1};
    spec.log = {"sonotrode"};
    spec.duration_s = 0.4;  // 8 bounces take 0.345 s
    spec.travel_fraction = travel_fraction;
    spec.scheme = scheme;
    const TestScene scene(spec);
    const auto model = scene.compile();
    Simulation sim(model);
    const double R = model->max_shot_radius_m;
    // Centre of the chamber: 9 mm from every wall, 18 mm below the ceiling at the start.
    sim.edit_state([&](SimulationState& edited) { set_shot(edited, 0, Vec3(0.0, 0.0, R + kH0), Vec3::Zero()); });

    const std::vector<ImpactRecord> impacts = run_collecting_impacts(sim);
    EXPECT_EQ(sim.state().health.serious(), 0u);
    const auto sono = static_cast<std::size_t>(model->sonotrode);
    EXPECT_EQ(sim.state().impacts_per_component[sono], impacts.size());

    DropErrors e;
    e.impacts = static_cast<int>(impacts.size());
    const double v1 = std::sqrt(2.0 * kG * kH0);
    double t_expected = std::sqrt(2.0 * kH0 / kG);
    for (int k = 0; k < std::min(kImpactsChecked, e.impacts); ++k) {
        const ImpactRecord& r = impacts[static_cast<std::size_t>(k)];
        const double v_in = std::pow(kC, k) * v1, v_out = kC * v_in;
        const double apex = std::pow(kC, 2 * (k + 1)) * kH0;
        e.time = std::max(e.time, std::abs(r.time_s - t_expected) / t_expected);
        e.speed_in = std::max(e.speed_in, std::abs(r.vn_in_m_per_s - v_in) / v_in);
        e.apex = std::max(e.apex, std::abs(r.vn_out_m_per_s * r.vn_out_m_per_s / (2.0 * kG) - apex) / apex);
        // Straight down onto the top face (z = 0 in the sonotrode's frame), below the drop point.
        EXPECT_NEAR(r.point_m.z(), 0.0, 1e-12) << "impact " << k;
        EXPECT_NEAR(r.point_m.x(), 0.0, 1e-12) << "impact " << k;
        EXPECT_NEAR(r.point_m.y(), 0.0, 1e-12) << "impact " << k;
        EXPECT_NEAR(r.vt_in_m_per_s, 0.0, 1e-12) << "impact " << k;
        t_expected += 2.0 * v_out / kG;
    }
    return e;
}

TEST(EngineBounce, DropOnStillSonotrodeMatchesClosedFormAndConverges) {
    const double fractions[] = {0.25, 0.1, 0.05};
    std::vector<DropErrors> errors;
    for (double f : fractions) {
        errors.push_back(drop(f));
        const DropErrors& e = errors.back();
        std::cout << "[ bounce   ] travel fraction " << f << ": " << e.impacts << " impacts; max relative error time " << e.time
                  << ", impact speed " << e.speed_in << ", apex " << e.apex << "\n";
        // Bounces continue until the approach falls below the resting speed 2 g dt: at least the 8 checked.
        EXPECT_GE(e.impacts, kImpactsChecked) << "travel fraction " << f;
        EXPECT_LT(e.time, 1e-9) << "travel fraction " << f;
        EXPECT_LT(e.speed_in, 1e-9) << "travel fraction " << f;
        EXPECT_LT(e.apex, 1e-9) << "travel fraction " << f;
    }
    // Non-increasing as the step shrinks, above a round-off floor of 1e-12 (errors at round-off
    // level move up and down by a few ulp with the step sequence).
    constexpr double floor = 1e-12;
    for (std::size_t i = 1; i < errors.size(); ++i) {
        EXPECT_LE(errors[i].time, std::max(errors[i - 1].time, floor)) << "fraction " << fractions[i];
        EXPECT_LE(errors[i].speed_in, std::max(errors[i - 1].speed_in, floor)) << "fraction " << fractions[i];
        EXPECT_LE(errors[i].apex, std::max(errors[i - 1].apex, floor)) << "fraction " << fractions[i];
    }
}

TEST(EngineBounce, DropOnStillSonotrodeMatchesClosedFormWithEventScheme) {
    // travel_fraction plays no part in the event scheme: each flight ends at the plane's exact touch.
    const DropErrors e = drop(0.25, "event");
    std::cout << "[ bounce   ] event scheme: " << e.impacts << " impacts; max relative error time " << e.time << ", impact speed "
              << e.speed_in << ", apex " << e.apex << "\n";
    EXPECT_GE(e.impacts, kImpactsChecked);
    EXPECT_LT(e.time, 1e-9);
    EXPECT_LT(e.speed_in, 1e-9);
    EXPECT_LT(e.apex, 1e-9);
}

}  // namespace
}  // namespace peensim::testing
