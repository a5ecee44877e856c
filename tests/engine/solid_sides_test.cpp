// A shot centre behind a face of a closed part is inside the part, whatever scheme steps it. The
// nearest point alone gives a normal from the surface to the centre, which for such a centre
// points further in: time stepping used to push the shot deeper and let it bounce about inside
// (the extremes matrix's 3072 shot of 2 mm: 355 impacts from inside the rod). Both schemes now
// read the side of the face (surface_clearance.h) and put the shot back out through it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/simulation.h"
#include "support/run_through_loop.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

constexpr double kShotR = 1e-3;  // m
constexpr double kTopZ = 12e-3;  // m, the box part's top face above the plate

class EngineSolidSides : public ::testing::TestWithParam<std::string> {};

TEST_P(EngineSolidSides, ACentreBehindATopFaceIsPutOutThroughIt) {
    TestSceneSpec spec;
    spec.scheme = GetParam();
    spec.duration_s = 0.05;
    PartSpec box;
    box.shape = PartShape::box;
    box.size_m = Vec3(6e-3, 6e-3, 4e-3);
    box.center_m = Vec3(0.0, 0.0, kTopZ - 2e-3);
    spec.part = box;
    spec.log = {"part"};
    const TestScene scene(spec);
    Simulation sim(scene.compile());
    // 0.3 R below the top face, 3 mm from the sides: the nearest point is on the top face, behind it.
    sim.edit_state([&](SimulationState& edited) { set_shot(edited, 0, Vec3(0.2e-3, -0.1e-3, kTopZ - 0.3 * kShotR), Vec3::Zero()); });
    std::size_t from_inside = 0;
    double lowest_after_first_step = 1.0;
    bool first = true;
    run_through_loop(sim, {.after_step = [&](const Simulation&, const std::vector<ImpactRecord>& impacts) {
                         for (const ImpactRecord& r : impacts) from_inside += r.v_in_m_per_s.z() > 0.0;  // hitting the top face from below
                         const double z = sim.state().shots.z[0];
                         if (!first) lowest_after_first_step = std::min(lowest_after_first_step, z);
                         first = false;
                     }});
    const ShotArrays& s = sim.state().shots;
    EXPECT_TRUE(s.active[0]);
    // Out through the top face, resting on it (a touch tolerance below kTopZ + R at most).
    EXPECT_NEAR(s.z[0], kTopZ + kShotR, 1e-6);
    EXPECT_GT(lowest_after_first_step, kTopZ + kShotR - 1e-6);
    EXPECT_EQ(from_inside, 0u);
}

INSTANTIATE_TEST_SUITE_P(Schemes, EngineSolidSides, ::testing::Values("step", "event"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace peensim::testing
