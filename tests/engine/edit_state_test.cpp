// Editing the state between steps (Simulation::edit_state) is seen by both schemes: a shot moved
// by hand mid-run flies from where it was put, never on the flight the scheme held before (the
// event-driven scheme keeps flights beside the state and used to overwrite such an edit).
#include <gtest/gtest.h>

#include "engine/simulation.h"
#include "support/test_scene.h"
#include "support/tube_scene.h"

namespace peensim::testing {
namespace {

class EditState : public ::testing::TestWithParam<std::string> {};

TEST_P(EditState, AShotMovedMidRunFallsFromWhereItWasPut) {
    // One 2 mm shot in a 10 mm tube 30 mm high, bouncing on the plate (A0 25 um) for 0.05 s; then
    // put at rest 20 mm up: it must be in free fall from there, z = z0 - g t^2 / 2, until it lands
    // (a 15 mm drop takes 55 ms; it is looked at after 20 ms).
    const double R = 1e-3;
    const TestScene scene(tube_scene(GetParam(), 10e-3, 30e-3, 1, R, 25e-6, 1.0));
    Simulation sim(scene.compile());
    sim.edit_state([&](SimulationState& s) { set_shot(s, 0, Vec3(0, 0, R + 1e-3), Vec3(0, 0, 0.5)); });
    // By hand: a step from a state edited mid-run is what is tested, and RunLoop ends only at restart points.
    std::vector<ImpactRecord> impacts;
    while (sim.state().time.seconds() < 0.05) sim.step(impacts, 0.05);
    ASSERT_GE(sim.state().time.seconds(), 0.05);
    const double t0 = sim.state().time.seconds();
    const Vec3 put(1e-3, -1e-3, 20e-3);
    sim.edit_state([&](SimulationState& s) {
        s.shots.set_position(0, put);
        s.shots.set_velocity(0, Vec3::Zero());
    });
    while (sim.state().time.seconds() < t0 + 0.02) sim.step(impacts, t0 + 0.02);
    const double t = sim.state().time.seconds() - t0;
    const Vec3 p = sim.state().shots.position(0), v = sim.state().shots.velocity(0);
    EXPECT_NEAR(p.z(), put.z() - 0.5 * kTubeGravity * t * t, 1e-12) << "t = " << t << " s after the edit";
    EXPECT_NEAR(p.x(), put.x(), 1e-15);
    EXPECT_NEAR(p.y(), put.y(), 1e-15);
    EXPECT_NEAR(v.z(), -kTubeGravity * t, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Schemes, EditState, ::testing::Values("step", "event"));

}  // namespace
}  // namespace peensim::testing
