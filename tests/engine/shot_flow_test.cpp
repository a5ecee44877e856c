// Shot sources and sinks (model/shot_flow.h, engine/shot_emitter.h): the box kernels against
// closed forms; the nozzle's emissions (times, disc, cone, determinism); and runs of the shipped
// nozzle scene with both schemes: every emitted shot accounted for (in the run, collected or
// lost), the first impact at the closed-form time of its flight, slots reused, and a run resumed
// from a checkpoint equal to the uninterrupted one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "engine/run_loop.h"
#include "engine/simulation.h"
#include "kernels/box_entry.h"
#include "model/model.h"
#include "model/nozzle_source.h"
#include "model/shot_flow.h"
#include "scene/scene_parser.h"
#include "support/files.h"
#include "support/run_in_process.h"
#include "support/run_through_loop.h"
#include "support/temp_dir.h"

namespace peensim::testing {
namespace {

const std::string kNozzleScene = std::string(PEENSIM_SOURCE_DIR) + "/scenes/nozzle-almen.yaml";

TEST(BoxEntry, FirstTimeInsideIsExact) {
    const Vec3 lo = Vec3::Zero(), hi = Vec3::Ones();
    // Already inside.
    EXPECT_EQ(*first_time_inside_box(Trajectory{Vec3(0.5, 0.5, 0.5), Vec3(1, 0, 0), Vec3::Zero(), 0.0}, lo, hi, 0.0, 10.0), 0.0);
    // A straight line through the x = 0 face at t = 1.
    EXPECT_DOUBLE_EQ(*first_time_inside_box(Trajectory{Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0), Vec3::Zero(), 0.0}, lo, hi, 0.0, 10.0), 1.0);
    // Falling onto the top face: z = 2 - t^2 reaches 1 at t = 1.
    EXPECT_DOUBLE_EQ(*first_time_inside_box(Trajectory{Vec3(0.5, 0.5, 2), Vec3::Zero(), Vec3(0, 0, -2), 0.0}, lo, hi, 0.0, 10.0), 1.0);
    // Thrown over the box: x = -1 + 2t, z = 0.5 + 4t - 2t^2 (apex 2.5 at t = 1, over x = 1): above
    // the box while x is in [0, 1], then down at x = 2: never inside.
    EXPECT_FALSE(first_time_inside_box(Trajectory{Vec3(-1, 0.5, 0.5), Vec3(2, 0, 4), Vec3(0, 0, -4), 0.0}, lo, hi, 0.0, 10.0));
    // The crossing lies beyond the interval.
    EXPECT_FALSE(first_time_inside_box(Trajectory{Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0), Vec3::Zero(), 0.0}, lo, hi, 0.0, 0.999));
    // Entering through an edge region: inside on x from t = 1, on z only from t = 2.
    EXPECT_DOUBLE_EQ(*first_time_inside_box(Trajectory{Vec3(-1, 0.5, -2), Vec3(1, 0, 1), Vec3::Zero(), 0.0}, lo, hi, 0.0, 10.0), 2.0);
}

TEST(BoxEntry, FirstTimeOutsideIsExact) {
    const Vec3 lo = Vec3::Zero(), hi = Vec3::Ones();
    EXPECT_DOUBLE_EQ(*first_time_outside_box(Trajectory{Vec3(0.5, 0.5, 0.5), Vec3(0, 0, 1), Vec3::Zero(), 0.0}, lo, hi, 0.0, 10.0), 0.5);
    // Up and back down, leaving through the floor: z = 0.5 + t - t^2 = 0 at t = (1 + sqrt 3) / 2.
    const auto t = first_time_outside_box(Trajectory{Vec3(0.5, 0.5, 0.5), Vec3(0, 0, 1), Vec3(0, 0, -2), 0.0}, lo, hi, 0.0, 10.0);
    EXPECT_NEAR(*t, 0.5 * (1.0 + std::sqrt(3.0)), 1e-15);
    EXPECT_EQ(*first_time_outside_box(Trajectory{Vec3(2, 0.5, 0.5), Vec3::Zero(), Vec3::Zero(), 0.0}, lo, hi, 3.0, 4.0), 3.0);
    EXPECT_FALSE(first_time_outside_box(Trajectory{Vec3(0.5, 0.5, 0.5), Vec3::Zero(), Vec3::Zero(), 0.0}, lo, hi, 0.0, 10.0));
}

TEST(NozzleSource, EmissionsAreEvenlyTimedOnTheDiscInTheConeAndTheSameEveryTime) {
    NozzleSpec spec;
    spec.plan.name = "n";
    spec.position_m = Vec3(0.01, -0.02, 0.05);
    spec.direction = Vec3(1, 1, -1).normalized();
    spec.exit_radius_m = 3e-3;
    spec.speed_m_per_s = 60.0;
    spec.spread_rad = 5.0 * M_PI / 180.0;
    spec.plan.rate_per_s = 1000.0;
    spec.plan.start_s = 0.25;
    spec.plan.stop_s = 10.25;
    const NozzleSource source(spec);
    double r2_sum = 0.0, cos_sum = 0.0;
    const int n = 10000;
    for (int k = 0; k < n; ++k) {
        const Emission e = *source.emission(static_cast<std::uint64_t>(k));
        EXPECT_DOUBLE_EQ(e.time_s, 0.25 + k / 1000.0);
        const Vec3 off = e.position_m - spec.position_m;
        EXPECT_NEAR(off.dot(spec.direction), 0.0, 1e-15);  // on the exit disc
        EXPECT_LE(off.norm(), spec.exit_radius_m * (1.0 + 1e-12));
        EXPECT_NEAR(e.velocity_m_per_s.norm(), 60.0, 1e-12);
        const double c = e.velocity_m_per_s.normalized().dot(spec.direction);
        EXPECT_GE(c, std::cos(spec.spread_rad) - 1e-12);  // in the cone
        r2_sum += off.squaredNorm();
        cos_sum += c;
        const Emission again = *source.emission(static_cast<std::uint64_t>(k));
        EXPECT_EQ(again.position_m, e.position_m);
        EXPECT_EQ(again.velocity_m_per_s, e.velocity_m_per_s);
    }
    // Uniform over the disc: mean r^2 = a^2 / 2; over the cap: mean cos = (1 + cos spread) / 2
    // (both within 4 standard errors of 10,000 draws).
    EXPECT_NEAR(r2_sum / n, 0.5 * 9e-6, 4.0 * 9e-6 / std::sqrt(12.0 * n));
    const double span = 1.0 - std::cos(spec.spread_rad);
    EXPECT_NEAR(cos_sum / n, 1.0 - 0.5 * span, 4.0 * span / std::sqrt(12.0 * n));
    EXPECT_FALSE(source.emission(10000));  // 0.25 + 10 s: the stop, excluded
}

// Exit speeds spread uniformly over v0 (1 +- spread): within the bounds, mean v0 and variance
// (v0 spread)^2 / 3 within 4 standard errors of 20,000 draws; the directions unchanged by it.
TEST(NozzleSource, ExitSpeedsAreUniformOverTheSpread) {
    NozzleSpec spec;
    spec.plan.name = "n";
    spec.speed_m_per_s = 100.0;
    spec.speed_spread = 0.05;
    spec.plan.rate_per_s = 1000.0;
    spec.plan.stop_s = 100.0;
    const NozzleSource source(spec);
    const int n = 20000;
    double sum = 0.0, sum2 = 0.0;
    for (int k = 0; k < n; ++k) {
        const Emission e = *source.emission(static_cast<std::uint64_t>(k));
        const double v = e.velocity_m_per_s.norm();
        EXPECT_GE(v, 95.0 - 1e-12);
        EXPECT_LE(v, 105.0 + 1e-12);
        EXPECT_NEAR(e.velocity_m_per_s.normalized().dot(spec.direction), 1.0, 1e-15);  // no cone
        sum += v;
        sum2 += v * v;
    }
    const double mean = sum / n, var = sum2 / n - mean * mean, var_expected = 25.0 / 3.0;
    EXPECT_NEAR(mean, 100.0, 4.0 * std::sqrt(var_expected / n));
    // The sample variance's standard error, sqrt((mu4 - sigma^4) / n) with mu4 = a^4 / 5 for a
    // uniform over +-a: 0.63 % of it here; 4 of them.
    EXPECT_NEAR(var, var_expected, 0.025 * var_expected);
}

struct FlowRun {
    std::vector<ImpactRecord> impacts;
    SimulationState state;
    std::shared_ptr<const Model> model;
};

FlowRun run_nozzle(const std::string& scheme, const std::string& duration) {
    FlowRun r;
    r.model = compile_model(parse_scene_file(kNozzleScene, {"accuracy.scheme=" + scheme, "process.duration=" + duration}));
    Simulation sim(r.model);
    RunLoop loop(sim);
    ImpactCollector collect;  // impacts are kept in the test: a small run
    loop.add(collect);
    EXPECT_TRUE(loop.run());
    r.impacts = std::move(collect.impacts);
    r.state = sim.state();
    return r;
}

class ShotFlow : public ::testing::TestWithParam<std::string> {};

TEST_P(ShotFlow, EveryEmittedShotIsInTheRunCollectedOrLost) {
    const FlowRun r = run_nozzle(GetParam(), "20 ms");
    const SimulationState& s = r.state;
    ASSERT_EQ(s.emitted_per_source.size(), 1u);
    EXPECT_EQ(s.emitted_per_source[0], 400u);  // 20,000 per s from t = 0, the one at 20 ms excluded
    std::uint64_t active = 0;
    for (unsigned char a : s.shots.active) active += a;
    EXPECT_EQ(active + s.collected_per_sink[0] + s.health.shot_lost + s.health.non_finite, 400u);
    EXPECT_GT(s.collected_per_sink[0], 300u);  // most have bounced off the strip and away
    EXPECT_EQ(s.health.serious(), 0u);
    // Slots are reused: the run never held more than the shot in flight at once (~0.6 ms of flight).
    std::cout << "[ flow     ] " << GetParam() << ": 400 emitted, " << s.collected_per_sink[0] << " collected, " << s.shots.size()
              << " slots\n";
    EXPECT_LT(s.shots.size(), 60u);
    EXPECT_GT(r.impacts.size(), 300u);
}

// Emission 0 leaves at t = 0 and falls freely onto the strip's face (z = 1.29 mm): its first
// impact comes when its centre is R above the face, z0 + vz t - g t^2 / 2 = 1.29 mm + R.
TEST_P(ShotFlow, TheFirstShotLandsAtTheClosedFormTimeOfItsFlight) {
    const FlowRun r = run_nozzle(GetParam(), "2 ms");
    const Emission e = *r.model->sources[0]->emission(0);
    const double R = r.model->max_shot_radius_m, g = 9.81;
    const double dz = e.position_m.z() - (1.29e-3 + R), vz = -e.velocity_m_per_s.z();  // down, m and m/s
    const double t = (-vz + std::sqrt(vz * vz + 2.0 * g * dz)) / g;
    const ImpactRecord* first = nullptr;
    for (const ImpactRecord& i : r.impacts)
        if (i.shot == 0 && (first == nullptr || i.time_s < first->time_s)) first = &i;
    ASSERT_NE(first, nullptr);
    EXPECT_NEAR(first->time_s, t, 1e-12);
    EXPECT_NEAR(first->vn_in_m_per_s, vz + g * t, 1e-9);
    const Vec3 landing = e.position_m + e.velocity_m_per_s * t;  // horizontally (gravity is vertical)
    EXPECT_NEAR(first->point_m.x(), landing.x(), 1e-9);
    EXPECT_NEAR(first->point_m.y(), landing.y(), 1e-9);
}

TEST_P(ShotFlow, AResumedRunEmitsAndCollectsAsTheUninterruptedOne) {
    TempDir dir;
    // Past the event-driven scheme's first restart point (0.1 s), where the stopped run checkpoints.
    const std::vector<std::string> set{"accuracy.scheme=" + GetParam(), "process.duration=150 ms"};
    const std::string whole = (dir.path / "whole").string(), parts = (dir.path / "parts").string();
    ASSERT_EQ(run_in_process({kNozzleScene, whole, false, false, {}, set}).code, kExitOk);
    const InProcessResult stopped = run_in_process({kNozzleScene, parts, false, false, 7, set});
    ASSERT_EQ(stopped.code, kExitInterrupted) << stopped.err;
    const InProcessResult resumed = run_in_process({kNozzleScene, parts, true, false, {}, set});
    ASSERT_EQ(resumed.code, kExitOk) << resumed.err;
    EXPECT_EQ(read_file(parts + "/impacts.csv"), read_file(whole + "/impacts.csv"));
    EXPECT_NE(read_file(whole + "/summary.json").find("\"collected\""), std::string::npos);
}

// A crowded jet (a 1 mm exit passing 50,000 shot per second at 20 m/s: 8 % of the exit's volume
// flow is shot; with first draws only, two centres came within 0.52 diameters): every shot starts
// clear of the others, which the schemes never have to separate.
class NoOverlapAtEmission : public RunListener {
public:
    explicit NoOverlapAtEmission(double radius_m) : diameter_(2.0 * radius_m) {}
    void after_step(const Simulation& sim, const std::vector<ImpactRecord>&) override {
        const ShotArrays& s = sim.state().shots;
        for (std::size_t i = 0; i < s.size(); ++i)
            for (std::size_t j = i + 1; j < s.size(); ++j)
                if (s.active[i] && s.active[j]) closest = std::min(closest, (s.position(i) - s.position(j)).norm() / diameter_);
    }
    double closest = 1e9;  // the closest two centres ever were, in shot diameters

private:
    double diameter_;
};

TEST_P(ShotFlow, ACrowdedNozzleStartsEveryShotClearOfTheOthers) {
    const auto model = compile_model(
        parse_scene_file(kNozzleScene, {"accuracy.scheme=" + GetParam(), "process.duration=3 ms", "sources[nozzle].exit_radius=0.5 mm",
                                        "sources[nozzle].rate=50000 1/s", "sources[nozzle].speed=20 m/s", "sources[nozzle].spread=0 deg"}));
    Simulation sim(model);
    RunLoop loop(sim);
    NoOverlapAtEmission check(model->max_shot_radius_m);
    loop.add(check);
    ASSERT_TRUE(loop.run());
    const SimulationState& s = sim.state();
    EXPECT_EQ(s.emitted_per_source[0], 150u);
    // The event scheme never lets two shot overlap; time stepping's collisions in the jet (speeds
    // +-5 %) overlap by at most a step's relative travel (a random start would overlap by up to a
    // diameter).
    if (GetParam() == "event") {
        EXPECT_GE(check.closest, 1.0 - 1e-9);
        EXPECT_EQ(s.health.shot_overlap_corrections, 0u);
    } else {
        EXPECT_GE(check.closest, 0.9);
    }
    EXPECT_EQ(s.health.serious(), 0u);
}

// Rebound scatter on the study's jet (100 m/s onto a plate, e = 0.4), its air blowing at the shot's
// speed as in the single-shot study's uniform flow: Re* = rho |u - v'| D / mu ~ 38.4 (100 + 40) =
// 5400, above 1500, and impacts above 40 m/s: rebounds leave the normal by up to the spread more
// than without, the run is the same twice, healthy.
TEST_P(ShotFlow, ReboundScatterTurnsFastRebounds) {
    const std::string study = std::string(PEENSIM_SOURCE_DIR) + "/scenes/nozzle-study.yaml";
    const auto run = [&](bool scatter) {
        std::vector<std::string> set{"accuracy.scheme=" + GetParam(), "process.duration=5 ms"};
        // (the jet's air moves no shot without drag: only the scatter reads it)
        if (scatter) set.insert(set.end(), {"air.rebound_scatter={spread: 20 deg}", "sources[nozzle].air_speed=100 m/s"});
        FlowRun r;
        r.model = compile_model(parse_scene_file(study, set));
        Simulation sim(r.model);
        RunLoop loop(sim);
        ImpactCollector collect;
        loop.add(collect);
        EXPECT_TRUE(loop.run());
        r.impacts = std::move(collect.impacts);
        EXPECT_EQ(sim.state().health.serious(), 0u);
        return r.impacts;
    };
    // The rebound's angle from the normal (deg), mean over the fast impacts.
    const auto mean_tilt = [](const std::vector<ImpactRecord>& impacts) {
        double sum = 0.0;
        int n = 0;
        for (const ImpactRecord& i : impacts)
            if (i.vn_in_m_per_s > 90.0) {
                sum += std::acos(std::min(1.0, i.vn_out_m_per_s / i.v_out_m_per_s.norm())) * 180.0 / M_PI, ++n;
            }
        return sum / std::max(n, 1);
    };
    const auto plain = run(false), scattered = run(true), again = run(true);
    ASSERT_GT(plain.size(), 200u);
    const double tilt_plain = mean_tilt(plain), tilt_scattered = mean_tilt(scattered);
    std::cout << "[ scatter  ] " << GetParam() << ": mean rebound tilt of impacts faster than 90 m/s " << tilt_plain
              << " deg, with a 20 deg scatter " << tilt_scattered << " deg\n";
    // Uniform in [0, 20] deg on top of the jet's own few degrees: about 10 deg more.
    EXPECT_GT(tilt_scattered, tilt_plain + 6.0);
    EXPECT_LT(tilt_scattered, tilt_plain + 14.0);
    ASSERT_EQ(again.size(), scattered.size());
    for (std::size_t k = 0; k < again.size(); ++k) EXPECT_EQ(again[k].v_out_m_per_s, scattered[k].v_out_m_per_s);
}

INSTANTIATE_TEST_SUITE_P(Schemes, ShotFlow, ::testing::Values("event", "step"));

}  // namespace
}  // namespace peensim::testing
