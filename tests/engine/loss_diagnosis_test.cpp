// A lost shot is diagnosed: through an opening of the assembly (a leak, with where) or through a
// surface the scheme missed (an engine error, with the surface and the point crossed).
#include <gtest/gtest.h>

#include <vector>

#include "app/run/loss_report.h"
#include "engine/loss_diagnosis.h"
#include "engine/simulation.h"
#include "support/run_through_loop.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

constexpr double kHalf = 10e-3;  // m, chamber half width (TestScene default 20 mm)

TEST(EngineLossDiagnosis, AShotThroughAGapBesideThePlateIsALeakShownWhereItLeft) {
    // The plate leaves a 2.2 mm gap to each side wall: narrower than the setup check's 1.25 D
    // (it passes), wide enough for a 2 mm shot dropped straight into it.
    TestSceneSpec spec;
    spec.scheme = "event";
    spec.plate_scale = 0.78;
    spec.duration_s = 0.1;
    const TestScene scene(spec);
    const auto model = scene.compile();
    Simulation sim(model);
    sim.edit_state([&](SimulationState& edited) { set_shot(edited, 0, Vec3(8.9e-3, 0.0, 10e-3), Vec3(0.0, 0.0, -1.0)); });
    run_through_loop(sim);
    const SimulationState& st = sim.state();
    ASSERT_EQ(st.lost.size(), 1u);
    const LostShot& l = st.lost.front();
    EXPECT_EQ(l.cause, LossCause::leak);
    EXPECT_EQ(st.health.engine_errors, 0u);
    EXPECT_EQ(st.health.shot_lost, 1u);
    // It left the chamber's and the plate's bounds at the bottom, in the gap.
    Vec3 lo = Vec3::Constant(1.0);
    for (const Component& c : model->components) lo = lo.cwiseMin(c.world_lo);
    EXPECT_NEAR(l.where_m.z(), lo.z(), 1e-9);
    EXPECT_NEAR(l.where_m.x(), 8.9e-3, 1e-9);
    EXPECT_GT(l.clearance_m, 1e-3);  // more than R: the sphere passed untouched
    const std::string text = describe_loss(*model, l);
    EXPECT_NE(text.find("opening"), std::string::npos) << text;
}

TEST(EngineLossDiagnosis, AFlightThroughAWallIsAnEngineErrorAtTheWall) {
    TestSceneSpec spec;
    const TestScene scene(spec);
    const auto model = scene.compile();
    // A flight the scheme cannot have made: from the middle straight through the closed +x wall.
    const Trajectory path{Vec3(0.0, 0.0, 10e-3), Vec3(5.0, 0.0, 0.0), Vec3::Zero(), 0.0};
    LostShot l;
    diagnose_loss(*model, SimTime{}, path, model->max_shot_radius_m, 0.0, 0.01, l);
    EXPECT_EQ(l.cause, LossCause::engine_error);
    EXPECT_EQ(model->components[static_cast<std::size_t>(l.component)].name, "chamber");
    EXPECT_NEAR(l.where_m.x(), kHalf, 1e-9);
    EXPECT_NEAR(l.where_m.z(), 10e-3, 1e-9);
    const std::string text = describe_loss(*model, l);
    EXPECT_NE(text.find("engine error"), std::string::npos) << text;
}

}  // namespace
}  // namespace peensim::testing
