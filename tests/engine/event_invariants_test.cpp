// Invariants of the event-driven scheme (accuracy.scheme: event), which resolves every contact at
// its exact time and so can promise what time stepping does not (time stepping resolves shot pairs
// at step ends and leaves overlaps: up to 1.7e-4 m measured at its step ends in the rod run below;
// and it takes slow approaches as sustained contact, losing their energy: 8e-6 relative in the box
// below):
//  - no overlaps: at frequent pauses (Simulation::step's pause_at_s, every 50 us), every pair of
//    active shot is at least 2R - 1e-9 m apart and every shot at least R - 1e-9 m from every
//    component mesh at its closed-form pose at that time; no shot lost;
//  - energy with gravity: with C = 1 everywhere (C0 = 1, V0 far above every speed, mu = 1) and a
//    still sonotrode, kinetic plus potential energy is kept to round-off through thousands of
//    shot-shot and wall impacts (the no-gravity box is EngineConservation's, for both schemes).
// And one every scheme must keep, run with both (accuracy.scheme step and event):
//  - pausing never changes the dynamics (stepper.h): a run paused every 50 us logs exactly the
//    impacts of the same run without pauses (what recording an animation relies on).
// Momentum of shot-shot impacts and same-seed determinism are EngineConservation's and
// EngineDeterminismSchemes', parametrised over the scheme there.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "engine/simulation.h"
#include "model/model.h"
#include "scene/scene_parser.h"
#include "support/overlap_check.h"
#include "support/run_report.h"
#include "support/run_through_loop.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

constexpr double kPause = 50e-6;            // s, between audited states (one sonotrode period at 20 kHz)
constexpr double kOverlapTolerance = 1e-9;  // m

TEST(EngineEventExact, NoOverlapsAndNoLostShotInTheRodScene) {
    // The shipped rod scene as it is (Table 1 coefficients, 512 shot, A 25 um), its first 0.06 s:
    // the bed leaves the plate and the first shot reach the rod (measured: ~3500 shot-shot impacts
    // and ~170 rod impacts in that time).
    const std::string scheme = "event";
    const auto model = compile_model(
        parse_scene_file(std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml", {"accuracy.scheme=" + scheme, "process.duration=0.06 s"}));
    const auto t0 = std::chrono::steady_clock::now();
    Simulation sim(model);
    OverlapAudit audit(*model, kOverlapTolerance);
    std::size_t rod_impacts = 0;
    audit.audit(sim.state());
    run_through_loop(sim, {.after_step =
                               [&](const Simulation& s, const std::vector<ImpactRecord>& impacts) {
                                   rod_impacts += impacts.size();
                                   audit.audit(s.state());
                               },
                           .pause_at_s = pause_every(kPause)});
    const SimulationState& st = sim.state();
    std::uint64_t wall = 0;
    for (std::uint64_t n : st.impacts_per_component) wall += n;
    std::cout << "[ overlaps ] " << scheme << " scheme, rod scene 0.06 s (" << seconds_since(t0) << " s wall): " << st.shot_shot_impacts
              << " shot-shot, " << wall << " mesh impacts (" << rod_impacts << " on the rod); " << audit.summary() << "; health "
              << health_text(st.health) << "\n";
    EXPECT_GT(st.shot_shot_impacts, 1000u);
    EXPECT_GT(rod_impacts, 0u);
    EXPECT_EQ(audit.report().pair_overlaps, 0u) << "first: " << audit.report().first_pair << "; deepest: " << audit.report().worst_pair;
    EXPECT_EQ(audit.report().mesh_overlaps, 0u) << "first: " << audit.report().first_mesh << "; deepest: " << audit.report().worst_mesh;
    EXPECT_EQ(st.health.shot_lost, 0u);
    EXPECT_EQ(st.health.serious(), 0u) << health_text(st.health);
}

// Kinetic plus potential energy per unit mass (J/kg): sum of v^2 / 2 - g . x.
double mechanical_energy_per_mass(const ShotArrays& s, const Vec3& g) {
    double e = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) e += 0.5 * s.velocity(i).squaredNorm() - g.dot(s.position(i));
    return e;
}

TEST(EngineEventExact, ElasticBoxWithGravityKeepsItsMechanicalEnergy) {
    // 50 shot of 2 mm thrown at 1 m/s in random upward directions in the closed 20 mm box, gravity
    // on, every contact perfectly elastic (C0 = 1, V0 1e6 m/s, mu = 1), still sonotrode, 0.5 s.
    // 1 m/s lifts a shot 51 mm, more than the box: they keep hitting the ceiling, walls, floor and
    // each other. Each impact and each parabola is exact up to roundings, so kinetic plus potential
    // energy must stay within 1e-9 relative of its start (audited every 1 ms and at every unit end). The
    // impact speed is 1 um/s, so that every contact is an impact.
    TestSceneSpec spec;
    spec.scheme = "event";
    spec.shot_count = 50;
    spec.initial_speed_m_per_s = 1.0;
    spec.duration_s = 0.5;
    spec.seed = 5;
    const PairSpec elastic{1.0, 1e6, 1.0, 0.1};
    spec.shot_shot = elastic;
    spec.sonotrode = elastic;
    spec.chamber = elastic;
    spec.log = {"sonotrode", "chamber"};
    const TestScene scene(spec);
    // Every contact an impact (contacts slower than the impact speed stop their approach: inelastic).
    const auto model = scene.compile({"accuracy.impact_speed=1e-6"});
    const auto t0 = std::chrono::steady_clock::now();
    Simulation sim(model);
    const Vec3 g = model->gravity_m_per_s2;
    const double e0 = mechanical_energy_per_mass(sim.state().shots, g);
    std::size_t wall_impacts = 0;
    double worst = 0.0, worst_at = 0.0;
    run_through_loop(sim, {.after_step =
                               [&](const Simulation& s, const std::vector<ImpactRecord>& impacts) {
                                   wall_impacts += impacts.size();
                                   const double change = std::abs(mechanical_energy_per_mass(s.state().shots, g) - e0) / e0;
                                   if (change > worst) worst = change, worst_at = s.state().time.seconds();
                               },
                           .pause_at_s = pause_every(1e-3)});
    const SimulationState& st = sim.state();
    std::cout << "[ energy g ] " << spec.scheme << " scheme (" << seconds_since(t0) << " s wall): " << st.steps << " units, "
              << st.shot_shot_impacts << " shot-shot and " << wall_impacts << " wall impacts; E0 " << e0 << " J/kg, worst relative change "
              << worst << " at t = " << worst_at << " s; health " << health_text(st.health) << "\n";
    EXPECT_GT(st.shot_shot_impacts, 200u);
    EXPECT_GT(wall_impacts, 500u);
    EXPECT_LT(worst, 1e-9);
    EXPECT_EQ(st.health.serious(), 0u) << health_text(st.health);
}

// The determinism test's small scene: 64 shot thrown up at 1 m/s and by the 25 um sonotrode onto a
// static rod 8 mm above the plate, 0.05 s, rod and sonotrode impacts logged.

std::vector<ImpactRecord> run_logging(const std::shared_ptr<const Model>& model, double pause_every_s) {
    Simulation sim(model);
    const std::vector<ImpactRecord> all = run_collecting_impacts(sim, {.pause_at_s = pause_every(pause_every_s)});
    EXPECT_EQ(sim.state().health.serious(), 0u) << health_text(sim.state().health);
    return all;
}

bool same(const ImpactRecord& a, const ImpactRecord& b) {
    return a.time_s == b.time_s && a.shot == b.shot && a.component == b.component && a.triangle == b.triangle && a.point_m == b.point_m &&
           a.v_in_m_per_s == b.v_in_m_per_s && a.vn_in_m_per_s == b.vn_in_m_per_s && a.vt_in_m_per_s == b.vt_in_m_per_s &&
           a.v_out_m_per_s == b.v_out_m_per_s && a.vn_out_m_per_s == b.vn_out_m_per_s;
}

class EngineEventInvariants : public ::testing::TestWithParam<std::string> {};

TEST_P(EngineEventInvariants, PausingDoesNotChangeTheImpacts) {
    TestSceneSpec spec = small_rod_scene(GetParam(), 0.05);
    spec.log = {"part", "sonotrode"};
    const TestScene scene(spec);
    const auto model = scene.compile();
    const std::vector<ImpactRecord> plain = run_logging(model, std::numeric_limits<double>::infinity());
    const std::vector<ImpactRecord> paused = run_logging(model, kPause);
    std::size_t first_difference = 0;
    while (first_difference < std::min(plain.size(), paused.size()) && same(plain[first_difference], paused[first_difference]))
        ++first_difference;
    std::cout << "[ pausing  ] " << GetParam() << " scheme: " << plain.size() << " impacts without pauses, " << paused.size()
              << " with a pause every " << kPause << " s; identical up to impact " << first_difference << "\n";
    ASSERT_GT(plain.size(), 100u);
    EXPECT_EQ(plain.size(), paused.size());
    EXPECT_EQ(first_difference, plain.size());
}

INSTANTIATE_TEST_SUITE_P(Schemes, EngineEventInvariants, ::testing::Values(std::string("step"), std::string("event")),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace peensim::testing
