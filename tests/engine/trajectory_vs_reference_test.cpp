// One shot, one start, event by event against the exact 1D reference
// (tests/support/vibrating_floor_reference.h): a 1 mm shot falls from the ceiling at 10 m/s and
// meets the floor (A 80 um, 20 kHz) as it moves down almost as fast, chatters on it 22 times
// (counted impacts from 0.32 down to 0.05 m/s, then slower touches), is caught and rides until
// the floor's deceleration passes gravity's, leaves at the floor's peak speed and bounces on
// between the floor and the ceiling. Chaos amplifies rounding ~10x per bounce after that, but the
// first 26 logged impacts are fixed to far better than 1e-11 s. Each must be the reference's: same
// surface, time to 1e-11 s, normal speed to 1e-9 relative.
//
// What it guards: every rule on the floor's slow side at once (the chatter followed down to the
// ride speed, the ride, the launch). A launch with the floor's velocity a few ns after the
// release (instead of the free flight from it) was 2e-6 m/s slow at 80 um; the ceiling impact that
// followed came 3.7e-10 s late.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "engine/run_loop.h"
#include "engine/simulation.h"
#include "support/test_scene.h"
#include "support/tube_scene.h"
#include "support/vibrating_floor_reference.h"

namespace peensim::testing {
namespace {

constexpr double kRadius = 0.5e-3;    // m
constexpr double kAmplitude = 80e-6;  // m
constexpr double kFrequency = kTubeFrequencyHz;
constexpr double kGravity = kTubeGravity;
constexpr double kHeight = 20e-3;       // m, ceiling above the floor's rest position
constexpr double kStartZ = 0.01910358;  // m, centre height at t = 0 (falling from the ceiling)
constexpr double kStartV = -10.18466;   // m/s
constexpr double kDuration = 0.03;      // s, well past the 26 compared impacts
constexpr std::size_t kCompared = 26;
constexpr double kTimeTolerance = 1e-11;  // s
constexpr double kSpeedTolerance = 1e-9;  // relative

struct Impact {
    double time_s;
    bool floor;
    double speed_m_per_s;
};

std::vector<Impact> engine_impacts(const std::string& scheme, std::uint64_t& rides) {
    const TestScene scene(tube_scene(scheme, 4e-3, kHeight, 1, kRadius, kAmplitude, kDuration));
    Simulation sim(scene.compile());
    sim.edit_state([&](SimulationState& edited) { set_shot(edited, 0, Vec3(0, 0, kStartZ), Vec3(0, 0, kStartV)); });
    struct Collect final : RunListener {
        std::vector<Impact> out;
        void after_step(const Simulation& s, const std::vector<ImpactRecord>& impacts) override {
            for (const ImpactRecord& r : impacts) out.push_back({r.time_s, r.component == s.model().sonotrode, r.vn_in_m_per_s});
        }
    } collect;
    RunLoop loop(sim);
    loop.add(collect);
    loop.run();
    std::vector<Impact> out = std::move(collect.out);
    rides = sim.scheme().stats().rides;
    return out;
}

struct ReferenceRun {
    std::vector<Impact> impacts;  // at or above the engine's impact speed, as the engine logs
    std::uint64_t captures = 0;
};

ReferenceRun reference_impacts(double impact_speed_m_per_s) {
    ReferenceRun run;
    VibratingFloorCase c{.R = kRadius,
                         .g = kGravity,
                         .A = kAmplitude,
                         .F = kFrequency,
                         .phase = 0.0,
                         .H = kHeight,
                         .z0 = kStartZ,
                         .v0 = kStartV,
                         .C0_floor = kTubeFloorPair.C0,
                         .V0_floor = kTubeFloorPair.V0_m_per_s,
                         .C0_ceiling = kTubeCeilingPair.C0,
                         .V0_ceiling = kTubeCeilingPair.V0_m_per_s,
                         .duration = kDuration};
    c.on_event = [&](const VibratingFloorEvent& e) {
        const bool floor = e.kind == VibratingFloorEventKind::floor_impact;
        if ((floor || e.kind == VibratingFloorEventKind::ceiling_impact) && e.speed >= impact_speed_m_per_s)
            run.impacts.push_back({e.time, floor, e.speed});
    };
    run.captures = simulate_vibrating_floor(c).floor_captures;
    return run;
}

class EngineTrajectoryVsReference : public ::testing::TestWithParam<std::string> {};

TEST_P(EngineTrajectoryVsReference, FirstImpactsThroughAChatterARideAndItsLaunchAreTheReferences) {
    std::uint64_t rides = 0;
    const std::vector<Impact> engine = engine_impacts(GetParam(), rides);
    const ReferenceRun reference = reference_impacts(0.05);
    ASSERT_GE(engine.size(), kCompared);
    ASSERT_GE(reference.impacts.size(), kCompared);
    // The case is what it says: a chatter of 22 counted floor impacts first, then a ride.
    for (std::size_t k = 0; k < 22; ++k) ASSERT_TRUE(reference.impacts[k].floor) << k;
    EXPECT_FALSE(reference.impacts[22].floor);
    EXPECT_EQ(reference.captures, 1u);
    if (GetParam() == "event") {
        EXPECT_EQ(rides, 1u);
    }
    for (std::size_t k = 0; k < kCompared; ++k) {
        const Impact& e = engine[k];
        const Impact& r = reference.impacts[k];
        EXPECT_EQ(e.floor, r.floor) << "impact " << k;
        EXPECT_NEAR(e.time_s, r.time_s, kTimeTolerance) << "impact " << k;
        EXPECT_NEAR(e.speed_m_per_s, r.speed_m_per_s, kSpeedTolerance * r.speed_m_per_s) << "impact " << k;
    }
}

INSTANTIATE_TEST_SUITE_P(Schemes, EngineTrajectoryVsReference, ::testing::Values(std::string("event"), std::string("step")),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace peensim::testing
