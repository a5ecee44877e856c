// The second kind of shot source, a hopper (model/hopper_source.h): shot drop at rest out of an
// opening at a steady rate. Its emissions (timing, place, no velocity, repeatable, a redraw moves
// the shot and keeps its time), and the whole path a new kind takes without its own code anywhere
// else: the scene section, the run (each scheme), the summary, `check`, a resume.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/check/check_job.h"
#include "app/exit_codes.h"
#include "engine/simulation.h"
#include "model/hopper_source.h"
#include "model/model.h"
#include "scene/scene_parser.h"
#include "support/files.h"
#include "support/run_in_process.h"
#include "support/run_through_loop.h"
#include "support/temp_dir.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

TEST(HopperSource, DropsEvenlyTimedShotAtRestUniformlyOverItsOpening) {
    HopperSpec spec;
    spec.plan.name = "feed";
    spec.opening_lo_m = Vec3(-0.01, 0.002, 0.05);
    spec.opening_hi_m = Vec3(0.01, 0.006, 0.05);  // flat in z: an opening in a plane
    spec.plan.rate_per_s = 500.0;
    spec.plan.start_s = 0.1;
    spec.plan.stop_s = 10.1;
    const HopperSource hopper(spec);
    const int n = 5000;
    Vec3 sum = Vec3::Zero();
    for (int k = 0; k < n; ++k) {
        const Emission e = *hopper.emission(static_cast<std::uint64_t>(k));
        EXPECT_DOUBLE_EQ(e.time_s, 0.1 + k / 500.0);
        EXPECT_EQ(e.velocity_m_per_s, Vec3::Zero());
        EXPECT_TRUE((e.position_m.array() >= spec.opening_lo_m.array()).all() && (e.position_m.array() <= spec.opening_hi_m.array()).all())
            << k;
        sum += e.position_m;
        EXPECT_EQ(hopper.emission(static_cast<std::uint64_t>(k))->position_m, e.position_m);  // the same every time
        const Emission redraw = *hopper.emission(static_cast<std::uint64_t>(k), 1);
        EXPECT_EQ(redraw.time_s, e.time_s);
        EXPECT_NE(redraw.position_m, e.position_m);
    }
    // Uniform over the box: the mean within 4 standard errors (side / sqrt(12 n)) of its centre.
    const Vec3 mean = sum / n, centre = 0.5 * (spec.opening_lo_m + spec.opening_hi_m);
    EXPECT_NEAR(mean.x(), centre.x(), 4.0 * 0.02 / std::sqrt(12.0 * n));
    EXPECT_NEAR(mean.y(), centre.y(), 4.0 * 0.004 / std::sqrt(12.0 * n));
    EXPECT_NEAR(mean.z(), 0.05, 1e-14);
    EXPECT_FALSE(hopper.emission(5000));  // 0.1 + 10 s: the stop, excluded
    const SourceOutline o = hopper.outline();
    EXPECT_EQ(o.kind, "hopper");
    EXPECT_FALSE(o.jet);  // no jet: no eps, no jet analysis
    EXPECT_EQ(o.fastest_speed_m_per_s, 0.0);
    EXPECT_EQ(o.start_lo_m, spec.opening_lo_m);
}

// A hopper 20 mm over the Almen strip of scenes/nozzle-almen.yaml in place of its nozzle.
std::string hopper_scene(const std::string& scheme) {
    return "name: Hopper over an Almen strip\n"
           "process: {duration: 150 ms, gravity: [0, 0, -9.81], seed: 1}\n"
           "accuracy: {scheme: " +
           scheme +
           "}\n"
           "shot: {count: 0, diameter: 0.58 mm, material: steel}\n"
           "materials:\n  steel: {density: 7.8 g/cm3}\n  SAE-1070: {density: 7.85 g/cm3}\n"
           "contacts:\n  shot-shot: {C0: 0.95, V0: 2.0 m/s}\n  shot-SAE-1070: {C0: 0.95, V0: 2.0 m/s, mu: 0.8, f: 0.1}\n"
           "components:\n  - name: almen\n    role: almen\n    mesh: " +
           std::string(PEENSIM_SOURCE_DIR) +
           "/assets/almen-strip-a.stl\n    mesh_unit: mm\n    material: SAE-1070\n    almen: {face_normal: [0, 0, 1]}\n"
           "sources:\n  - name: feed\n    kind: hopper\n    opening_min: [-3 mm, -3 mm, 21.29 mm]\n"
           "    opening_max: [3 mm, 3 mm, 21.29 mm]\n    rate: 2000 1/s\n"
           "sinks:\n  - name: away\n    region: outside\n";
}

class HopperRun : public ::testing::TestWithParam<std::string> {};

// Each shot falls 20 mm from rest onto the strip: its first impact sqrt(2 h / g) = 64 ms after it left,
// at g t, straight below where it left; every shot emitted is in the run, collected or lost.
TEST_P(HopperRun, ShotFallFromRestOntoTheStripAtTheClosedFormTimeAndSpeed) {
    TempDir dir;
    const fs::path scene = dir.path / "hopper.yaml";
    std::ofstream(scene) << hopper_scene(GetParam());
    const auto model = compile_model(parse_scene_file(scene.string()));
    ASSERT_EQ(model->sources.size(), 1u);
    Simulation sim(model);
    const std::vector<ImpactRecord> impacts = run_collecting_impacts(sim);
    const SimulationState& s = sim.state();
    EXPECT_EQ(s.emitted_per_source[0], 300u);  // 2000 per s for 150 ms
    std::uint64_t active = 0;
    for (unsigned char a : s.shots.active) active += a;
    EXPECT_EQ(active + s.collected_per_sink[0] + s.health.shot_lost + s.health.non_finite, 300u);
    EXPECT_EQ(s.health.serious(), 0u);
    const double R = model->max_shot_radius_m, g = 9.81;
    for (std::uint64_t k : {0u, 1u}) {  // (later ones may meet the first ones rebounding)
        const Emission e = *model->sources[0]->emission(k);
        const double t = std::sqrt(2.0 * (e.position_m.z() - (1.29e-3 + R)) / g);  // fall time
        // Emission k takes slot k (no shot before it, none collected yet); its first impact:
        const ImpactRecord* first = nullptr;
        for (const ImpactRecord& i : impacts)
            if (i.shot == static_cast<int>(k) && (first == nullptr || i.time_s < first->time_s)) first = &i;
        ASSERT_NE(first, nullptr) << "emission " << k;
        // (The strip's face is at 1.29 mm in single precision, 3.8e-11 m lower: 6e-11 s of fall.)
        EXPECT_NEAR(first->time_s, e.time_s + t, 1e-9);
        EXPECT_NEAR(first->point_m.x(), e.position_m.x(), 1e-9);
        EXPECT_NEAR(first->vn_in_m_per_s, g * t, 1e-9);
        EXPECT_NEAR(first->point_m.y(), e.position_m.y(), 1e-9);
    }
}

INSTANTIATE_TEST_SUITE_P(Schemes, HopperRun, ::testing::Values("event", "step"));

// What the rest of peensim says of a hopper, from the ShotSource interface alone: `check`, the run's
// summary (its emissions counted, no jet figure), a resumed run the uninterrupted one.
TEST(HopperRun, CheckSummaryAndResumeFollowThroughTheInterface) {
    TempDir dir;
    const fs::path scene = dir.path / "hopper.yaml";
    std::ofstream(scene) << hopper_scene("event");
    std::ostringstream out, err;
    ASSERT_EQ(check_job(scene.string(), {"process.duration=150 ms"}, false, out, err), kExitOk) << err.str();
    EXPECT_NE(out.str().find("# source feed (hopper): 2000 shot/s dropped at rest from the box (-3, -3, 21.29) mm to (3, 3, 21.29) mm, "
                             "from 0 s to 0.15 s (300 shot at most)"),
              std::string::npos)
        << out.str();
    EXPECT_NE(out.str().find("kind: hopper"), std::string::npos);  // the resolved scene
    const std::vector<std::string> set{"process.duration=150 ms"};
    const std::string whole = (dir.path / "whole").string(), parts = (dir.path / "parts").string();
    ASSERT_EQ(run_in_process({scene.string(), whole, false, false, {}, set}).code, kExitOk);
    const InProcessResult stopped = run_in_process({scene.string(), parts, false, false, 7, set});
    ASSERT_EQ(stopped.code, kExitInterrupted) << stopped.err;
    ASSERT_EQ(run_in_process({scene.string(), parts, true, false, {}, set}).code, kExitOk);
    EXPECT_EQ(read_file(parts + "/impacts.csv"), read_file(whole + "/impacts.csv"));
    const std::string summary = read_file(whole + "/summary.json");
    EXPECT_NE(summary.find("\"feed\""), std::string::npos) << summary;
    EXPECT_EQ(summary.find("flow_rate_eps\": [{"), std::string::npos) << summary;  // no jet, no eps
}

}  // namespace
}  // namespace peensim::testing
