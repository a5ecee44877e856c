// Mesh sinks (model/mesh_sink.h): inside and outside a closed mesh by its winding number; the entry
// of a flight into it at the closed-form time (straight and falling); an open mesh refused; and a
// run where a horizontal jet flies into a closed box outlet: every shot that reached it collected
// by it (none lost, none by the bounds), with both schemes.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <string>

#include "engine/simulation.h"
#include "geometry/box_mesh.h"
#include "geometry/stl_writer.h"
#include "model/mesh_sink.h"
#include "model/model.h"
#include "scene/scene_parser.h"
#include "support/run_through_loop.h"
#include "support/temp_dir.h"

namespace peensim {
namespace {

std::shared_ptr<const TriangleMesh> cube(const Vec3& centre, double edge, int divisions) {
    BoxSpec spec;
    spec.size_m = Vec3::Constant(edge);
    spec.center_m = centre;
    spec.divisions = Eigen::Vector3i::Constant(divisions);
    return std::make_shared<const TriangleMesh>(box(spec));
}

TEST(MeshSink, InsideIsTheWindingNumber) {
    const MeshSink sink("bin", cube(Vec3(0.1, 0.2, 0.3), 0.02, 3));
    EXPECT_NEAR(sink.winding_number(Vec3(0.1, 0.2, 0.3)), 1.0, 1e-12);
    EXPECT_NEAR(sink.winding_number(Vec3(0.109, 0.191, 0.3)), 1.0, 1e-12);
    EXPECT_NEAR(sink.winding_number(Vec3(0.2, 0.2, 0.3)), 0.0, 1e-12);
    EXPECT_TRUE(sink.contains(Vec3(0.1, 0.2, 0.3)));
    EXPECT_TRUE(sink.contains(Vec3(0.1099, 0.2, 0.3)));
    EXPECT_FALSE(sink.contains(Vec3(0.1101, 0.2, 0.3)));
    EXPECT_FALSE(sink.contains(Vec3(5, 5, 5)));
}

TEST(MeshSink, AFlightEntersAtTheClosedFormTime) {
    const MeshSink sink("bin", cube(Vec3::Zero(), 0.02, 2));  // faces at +-10 mm
    // Straight along x from -0.1 m at 30 m/s: within reach (1 nm) of the face x = -0.01 at
    // t = (0.09 - 1 nm) / 30 s.
    const auto straight = sink.first_entry(Trajectory{Vec3(-0.1, 0.001, 0.002), Vec3(30, 0, 0), Vec3::Zero(), 0.0}, 0.0, 1.0);
    ASSERT_TRUE(straight);
    EXPECT_NEAR(*straight, (0.09 - MeshSink::kSurfaceReach) / 30.0, 1e-16);
    // Dropped from 50 mm above: z = 0.05 - 4.905 t^2 comes within 1 nm of the top face z = 0.01 at
    // sqrt((0.04 - 1 nm) / 4.905).
    const auto fall = sink.first_entry(Trajectory{Vec3(0.003, -0.004, 0.05), Vec3::Zero(), Vec3(0, 0, -9.81), 0.0}, 0.0, 1.0);
    ASSERT_TRUE(fall);
    EXPECT_NEAR(*fall, std::sqrt((0.04 - MeshSink::kSurfaceReach) / 4.905), 1e-15);
    // Passing beside it: never; starting inside (at the centre at t = 0.25 on the path's clock): at once.
    EXPECT_FALSE(sink.first_entry(Trajectory{Vec3(-0.1, 0.02, 0.0), Vec3(30, 0, 0), Vec3::Zero(), 0.0}, 0.0, 1.0));
    const auto inside = sink.first_entry(Trajectory{Vec3(0.0, 0.0, 0.0), Vec3(30, 0, 0), Vec3::Zero(), 0.25}, 0.25, 1.0);
    ASSERT_TRUE(inside);
    EXPECT_EQ(*inside, 0.25);
}

TEST(MeshSink, AnOpenMeshIsRefused) {
    BoxSpec spec;
    spec.size_m = Vec3::Constant(0.01);
    const auto open = std::make_shared<const TriangleMesh>(box_open(spec, BoxFace::plus_z, Facing::outward));
    EXPECT_THROW(MeshSink("bin", open), std::invalid_argument);
}

// No part: a nozzle at the origin blowing along +x at 20 m/s into a 20 mm box outlet whose near
// face is 49 mm away; gravity along -z. Every shot is collected by the outlet.
TEST(MeshSink, AJetIntoABoxOutletIsCollectedByIt) {
    testing::TempDir dir;
    write_binary_stl(*cube(Vec3(59e-3, 0, 0), 20e-3, 2), (dir.path / "bin.stl").string(), 1e-3);
    {
        std::ofstream scene(dir.path / "jet.yaml");
        scene << R"(process: {duration: 20 ms, gravity: [0, 0, -9.81], seed: 3}
shot: {count: 0, diameter: 0.6 mm, density: 7.8 g/cm3}
components:
  - {name: plate, role: part, mesh: bin.stl, mesh_unit: mm, translation: [0, 0, -100 mm]}
sources:
  - {name: nozzle, position: [0, 0, 0], direction: [1, 0, 0], speed: 20 m/s, speed_spread: 0, rate: 2000 1/s, diameter: 2 mm}
sinks:
  - {name: bin, region: mesh, mesh: bin.stl, mesh_unit: mm}
  - {name: away, region: outside}
)";
    }
    for (const char* scheme : {"event", "step"}) {
        const auto model = compile_model(parse_scene_file((dir.path / "jet.yaml").string(), {std::string("accuracy.scheme=") + scheme}));
        Simulation sim(model);
        const std::vector<ImpactRecord> impacts = testing::run_collecting_impacts(sim);
        const SimulationState& s = sim.state();
        // 40 emitted in 20 ms (k / 2000 s); a shot reaches the outlet's face 49 mm away 2.45 ms after
        // it left (falling 29 um meanwhile), so k = 0..35 are collected, 36..39 still on their way.
        EXPECT_EQ(s.emitted_per_source[0], 40u) << scheme;
        std::uint64_t in_run = 0;
        for (unsigned char a : s.shots.active) in_run += a;
        EXPECT_EQ(s.collected_per_sink[0] + in_run, 40u) << scheme;
        EXPECT_EQ(s.collected_per_sink[0], 36u) << scheme;
        EXPECT_EQ(s.collected_per_sink[1], 0u) << scheme;
        EXPECT_TRUE(impacts.empty()) << scheme;
        EXPECT_EQ(s.health.serious(), 0u) << scheme;
    }
}

}  // namespace
}  // namespace peensim
