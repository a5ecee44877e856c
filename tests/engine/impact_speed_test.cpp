// The one line between impacts and sustained contact (accuracy.impact_speed): a shot dropped from
// rest onto the still sonotrode with a constant restitution C bounces with approach speeds
// v_k = C^(k-1) v1 (v1 = sqrt(2 g h0)), at t1 = sqrt(2 h0 / g), t(k+1) = t(k) + 2 C v_k / g. Exactly
// the bounces with v_k >= impact speed are impacts (logged, each at its closed-form time); the
// next landing is sustained contact: no rebound, one slow contact, then the shot rests on the
// plate (counted once, however long it lies there). The count follows from C, v1 and the
// threshold: N = floor(ln(v_imp / v1) / ln C) + 1.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/check/check_job.h"
#include "app/run/run_job.h"
#include "engine/simulation.h"
#include "engine/time_stepping.h"
#include "support/run_through_loop.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

constexpr double kGravityAcceleration = 9.81;  // m/s2
constexpr double kH0 = 2e-3;                   // m, drop height of the centre above its height at contact
constexpr double kC = 0.8;                     // -, shot-sonotrode restitution (V0 1000 m/s: always elastic)

TestSceneSpec still_plate(const std::string& scheme = "step") {
    TestSceneSpec spec;
    spec.chamber_size_m = Vec3(20e-3, 20e-3, 30e-3);
    spec.amplitude_m = 0.0;
    spec.sonotrode = {kC, 1e3, 0.71, 0.1};
    spec.log = {"sonotrode"};
    spec.duration_s = 0.5;  // the bounces are over after ~0.2 s; the shot then rests 0.3 s
    spec.scheme = scheme;
    return spec;
}

// Bounces the closed form says are impacts at this threshold (m/s).
int expected_impacts(double impact_speed) {
    const double v1 = std::sqrt(2.0 * kGravityAcceleration * kH0);
    return static_cast<int>(std::floor(std::log(impact_speed / v1) / std::log(kC))) + 1;
}

struct Drop {
    std::vector<ImpactRecord> impacts;
    SimulationState state;
    double R = 0.0;
    double largest_step_s = 0.0;  // s
    std::string scheme;
    std::size_t sonotrode = 0;
};

Drop drop(const std::vector<std::string>& overrides, const std::string& scheme = "step") {
    const TestScene scene(still_plate(scheme));
    const auto model = scene.compile(overrides);
    Simulation sim(model);
    Drop d;
    d.scheme = scheme;
    d.R = model->max_shot_radius_m;
    d.sonotrode = static_cast<std::size_t>(model->sonotrode);
    sim.edit_state([&](SimulationState& edited) { set_shot(edited, 0, Vec3(0.0, 0.0, d.R + kH0), Vec3::Zero()); });
    double before = sim.state().time.seconds();  // s, the step's start
    d.impacts = run_collecting_impacts(sim, {.after_step = [&](const Simulation&, const std::vector<ImpactRecord>&) {
                                           d.largest_step_s = std::max(d.largest_step_s, sim.state().time.seconds() - before);
                                           before = sim.state().time.seconds();
                                       }});
    d.state = sim.state();
    EXPECT_EQ(d.state.health.serious(), 0u);
    return d;
}

void expect_closed_form(const Drop& d, double impact_speed) {
    const int n = expected_impacts(impact_speed);
    ASSERT_EQ(static_cast<int>(d.impacts.size()), n) << "impact speed " << impact_speed << " m/s";
    const double v1 = std::sqrt(2.0 * kGravityAcceleration * kH0);
    double t = std::sqrt(2.0 * kH0 / kGravityAcceleration);
    for (int k = 0; k < n; ++k) {
        const ImpactRecord& r = d.impacts[static_cast<std::size_t>(k)];
        const double v_in = std::pow(kC, k) * v1;
        EXPECT_GE(r.vn_in_m_per_s, impact_speed) << "impact " << k;
        EXPECT_NEAR(r.time_s, t, 1e-12) << "impact " << k;
        EXPECT_NEAR(r.vn_in_m_per_s, v_in, 1e-12) << "impact " << k;
        EXPECT_NEAR(r.vn_out_m_per_s, kC * v_in, 1e-12) << "impact " << k;
        t += 2.0 * kC * v_in / kGravityAcceleration;
    }
    // The next landing (slower than the threshold) ended the bouncing: once counted, then rest.
    EXPECT_LT(std::pow(kC, n) * v1, impact_speed);
    EXPECT_EQ(d.state.impacts_per_component[d.sonotrode], static_cast<std::uint64_t>(n));
    EXPECT_EQ(d.state.slow_contacts_per_component[d.sonotrode], 1u);
    std::uint64_t slow = d.state.shot_shot_slow_contacts;
    for (std::uint64_t c : d.state.slow_contacts_per_component) slow += c;
    EXPECT_EQ(slow, 1u);
    EXPECT_NEAR(d.state.shots.z[0], d.R, 1e-9);
    EXPECT_LT(std::abs(d.state.shots.vz[0]), 1e-3 * impact_speed);
    // Time stepping: gravity adds at most a tenth of the threshold per step.
    if (d.scheme == "step") {
        EXPECT_LE(d.largest_step_s * kGravityAcceleration, 0.1 * impact_speed * (1.0 + 1e-12));
    }
    std::cout << "[ impact speed ] " << impact_speed << " m/s: " << d.impacts.size() << " impacts, last at "
              << d.impacts.back().vn_in_m_per_s << " m/s, then 1 slow contact; largest step " << d.largest_step_s * 1e6 << " us\n";
}

// Both schemes draw the line at the same place: each logs exactly the closed form's bounces.
class EngineImpactSpeedSchemes : public ::testing::TestWithParam<std::string> {};

TEST_P(EngineImpactSpeedSchemes, ADroppedShotLogsExactlyTheBouncesFasterThanTheDefaultThresholdThenRests) {
    EXPECT_EQ(expected_impacts(0.05), 7);
    expect_closed_form(drop({}, GetParam()), 0.05);
}

TEST_P(EngineImpactSpeedSchemes, ALowerThresholdSetInTheSceneLogsMoreBounces) {
    EXPECT_EQ(expected_impacts(0.01), 14);
    expect_closed_form(drop({"accuracy.impact_speed=1 cm/s"}, GetParam()), 0.01);
}

INSTANTIATE_TEST_SUITE_P(Schemes, EngineImpactSpeedSchemes, ::testing::Values("step", "event"));

TEST(EngineImpactSpeed, BothSchemesLogTheSameSequence) {
    const Drop step = drop({}, "step"), event = drop({}, "event");
    ASSERT_EQ(step.impacts.size(), event.impacts.size());
    for (std::size_t k = 0; k < step.impacts.size(); ++k) {
        EXPECT_NEAR(step.impacts[k].time_s, event.impacts[k].time_s, 1e-12) << "impact " << k;
        EXPECT_NEAR(step.impacts[k].vn_in_m_per_s, event.impacts[k].vn_in_m_per_s, 1e-12) << "impact " << k;
    }
    EXPECT_EQ(step.state.slow_contacts_per_component, event.state.slow_contacts_per_component);
}

TEST(EngineImpactSpeed, TheStepIsCappedSoGravityAddsATenthOfTheThresholdAtMost) {
    const TestScene scene(still_plate());
    const auto model = scene.compile({"accuracy.impact_speed=2 cm/s"});
    EXPECT_DOUBLE_EQ(model->impact_speed_m_per_s, 0.02);
    // A still shot on a still plate: eq. 7 alone would give 4.5 ms.
    EXPECT_GT(TimeStepping::step_for(0.0, kGravityAcceleration, 0.25 * model->max_shot_radius_m), 4e-3);
    EXPECT_DOUBLE_EQ(TimeStepping::time_step(*model, 0.0), 0.1 * 0.02 / kGravityAcceleration);
    // Fast shot: eq. 7 decides.
    EXPECT_DOUBLE_EQ(TimeStepping::time_step(*model, 10.0),
                     TimeStepping::step_for(10.0, kGravityAcceleration, 0.25 * model->max_shot_radius_m));
}

TEST(EngineImpactSpeed, TheSummaryCountsSlowContactsPerComponent) {
    TestSceneSpec spec = still_plate();
    spec.duration_s = 0.3;
    const TestScene scene(spec);
    // The run places its own shot on the plate at rest: throw it up by 2 mm instead.
    RunOptions o;
    o.scene_path = scene.scene_path();
    o.output_dir = scene.make_subdirectory("out");
    o.progress = false;
    o.analyze = false;
    o.overrides = {"shot.initial_velocity=[0, 0, " + std::to_string(std::sqrt(2.0 * kGravityAcceleration * kH0)) + "]"};
    std::ostringstream out, err;
    ASSERT_EQ(run_job(o, out, err), kExitOk) << err.str();
    std::ifstream in(o.output_dir + "/summary.json");
    const auto j = nlohmann::json::parse(in);
    const auto& slow = j.at("slow_contacts_per_component");
    const auto& impacts = j.at("impacts_per_component");
    ASSERT_EQ(slow.size(), impacts.size());
    for (std::size_t k = 0; k < slow.size(); ++k) {
        EXPECT_EQ(slow[k].at("component"), impacts[k].at("component"));
        const std::uint64_t expected = slow[k].at("component") == "sonotrode" ? 1u : 0u;
        EXPECT_EQ(slow[k].at("slow_contacts").get<std::uint64_t>(), expected) << slow[k];
    }
    EXPECT_EQ(j.at("impact_speed_mps").get<double>(), 0.05);
    EXPECT_NE(out.str().find("slow contacts"), std::string::npos) << out.str();
    EXPECT_NE(out.str().find("sonotrode 1 (landings slower than 0.05 m/s)"), std::string::npos) << out.str();
}

// Bad values are refused like every other scene field: file, line, field, exit code 2.
TEST(EngineImpactSpeed, BadThresholdsAreInputErrors) {
    const std::string dir = std::string(PEENSIM_SOURCE_DIR) + "/tests/scenes_bad/";
    for (const char* file : {"impact_speed_zero.yaml", "impact_speed_negative.yaml", "impact_speed_not_a_speed.yaml"}) {
        std::ostringstream out, err;
        EXPECT_EQ(check_job(dir + file, {}, false, out, err), kExitInputError) << file;
        EXPECT_NE(err.str().find(std::string(file) + ":3:"), std::string::npos) << err.str();
        EXPECT_NE(err.str().find("accuracy.impact_speed: "), std::string::npos) << err.str();
    }
}

}  // namespace
}  // namespace peensim::testing
