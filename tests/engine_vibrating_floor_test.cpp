// The engine's vibrating sonotrode against the exact event-driven reference
// (tests/support/vibrating_floor_reference.h): one shot bouncing vertically between the vibrating
// floor (A 25 um, 20 kHz) and the chamber's static ceiling 20 mm above it.
//
// A single shot's statistics are chaotic and have a long memory (the reference's author measured
// 10-17 % between 5 s windows of one run), so the engine runs 16 independent shot side by side
// (5 mm apart, moving only vertically: they never meet each other or a wall), each from its own
// starting height, and the reference runs the same 16 starts for much longer. Rates and mean normal
// speeds are compared with a statistical bound: the difference of the means must stay within
// 3 standard errors (from the spread over the 16 engine shot and the reference's own spread).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "engine/simulation.h"
#include "support/test_scene.h"
#include "support/vibrating_floor_reference.h"

namespace peensim::testing {
namespace {

constexpr double kR = 1e-3;            // m, shot radius (D = 2 mm)
constexpr double kA = 25e-6;           // m, sonotrode amplitude
constexpr double kF = 20e3;            // Hz
constexpr double kH = 20e-3;           // m, ceiling height above the plate's rest position
constexpr double kG = 9.81;            // m/s2
constexpr double kStart = 0.5;         // s, statistics start (after the start-up transient)
const double kEngineEnd = std::getenv("ENG_END") ? std::atof(std::getenv("ENG_END")) : 3.0;     // s, engine run length
const double kReferenceEnd = std::getenv("REF_END") ? std::atof(std::getenv("REF_END")) : 60.0; // s, reference run length per start
constexpr int kGrid = 4;               // 4 x 4 shot
constexpr double kSpacing = 5e-3;      // m, between shot centres

// Per-shot statistics over [kStart, end].
struct ShotStats {
    double floor_rate = 0.0;     // 1/s
    double floor_speed = 0.0;    // m/s, mean normal impact speed
    double ceiling_rate = 0.0;   // 1/s
    double ceiling_speed = 0.0;  // m/s
};

struct MeanAndError {
    double mean = 0.0;
    double standard_error = 0.0;
};

template <class Field>
MeanAndError over_shots(const std::vector<ShotStats>& shots, Field field) {
    double sum = 0.0, sum2 = 0.0;
    for (const ShotStats& s : shots) sum += field(s);
    const double n = static_cast<double>(shots.size());
    const double mean = sum / n;
    for (const ShotStats& s : shots) sum2 += (field(s) - mean) * (field(s) - mean);
    return {mean, std::sqrt(sum2 / (n - 1.0) / n)};
}

double start_height(int i) { return kR + 1e-3 * (i + 1); }  // m, 2 ... 17 mm: distinct starts

std::vector<ShotStats> engine_statistics() {
    TestSceneSpec spec;
    spec.chamber_size_m = Vec3(kGrid * kSpacing, kGrid * kSpacing, kH);
    spec.shot_count = kGrid * kGrid;
    spec.shot_diameter_m = 2.0 * kR;
    spec.amplitude_m = kA;
    spec.frequency_hz = kF;
    spec.gravity_m_per_s2 = Vec3(0, 0, -kG);
    spec.duration_s = kEngineEnd;
    spec.sonotrode = {0.9, 1.5, 0.71, 0.1};  // titanium floor
    spec.chamber = {0.95, 2.0, 0.71, 0.1};   // steel ceiling
    spec.log = {"sonotrode", "chamber"};
    if (std::getenv("TF")) spec.travel_fraction = std::atof(std::getenv("TF"));
    const TestScene scene(spec);
    const auto model = scene.compile();
    Simulation sim(model);
    for (int i = 0; i < kGrid * kGrid; ++i) {
        const double x = (i % kGrid - 0.5 * (kGrid - 1)) * kSpacing, y = (i / kGrid - 0.5 * (kGrid - 1)) * kSpacing;
        set_shot(sim.mutable_state(), static_cast<std::size_t>(i), Vec3(x, y, start_height(i)), Vec3::Zero());
    }
    const auto sono = model->sonotrode;
    std::vector<ShotStats> stats(static_cast<std::size_t>(kGrid * kGrid));
    std::vector<ImpactRecord> impacts;
    std::size_t wall_hits = 0;
    std::size_t missed = 0; double worst_gap = 0.0;
    const Kinematics& kin = model->sonotrode_component().kinematics;
    while (!sim.finished()) {
        const ShotArrays before = sim.state().shots;
        const SimTime t0 = sim.state().time;
        sim.step(impacts);
        const double dt = sim.state().time.seconds() - t0.seconds();
        std::vector<int> hit(16, 0);
        for (const ImpactRecord& r : impacts) hit[r.shot] = 1;
        for (int i = 0; i < 16; ++i) {
            if (hit[i]) continue;
            const double z0 = before.z[i], v0 = before.vz[i];
            if (sim.state().shots.vz[i] != v0 - kG * dt) continue;
            double g_min = 1.0;
            for (int k = 1; k <= 256; ++k) {
                const double u = dt * k / 256;
                g_min = std::min(g_min, z0 + v0 * u - 0.5 * kG * u * u - kR - kin.displacement(t0, u));
            }
            if (g_min < -1e-9) { ++missed; worst_gap = std::min(worst_gap, g_min); }
        }
        for (const ImpactRecord& r : impacts) {
            if (r.time_s < kStart) continue;
            ShotStats& s = stats[static_cast<std::size_t>(r.shot)];
            if (r.component == sono) {
                s.floor_rate += 1.0;
                s.floor_speed += r.vn_in_m_per_s;
            } else if (std::abs(r.point_m.z() - kH) < 1e-9) {
                s.ceiling_rate += 1.0;
                s.ceiling_speed += r.vn_in_m_per_s;
            } else {
                ++wall_hits;
            }
        }
        impacts.clear();
    }
    std::cout << "missed " << missed << " worst " << worst_gap << "\n";
    EXPECT_EQ(wall_hits, 0u) << "a shot left its vertical line";
    EXPECT_EQ(sim.state().shot_shot_impacts, 0u);
    EXPECT_EQ(sim.state().health.serious(), 0u);
    // Still on their vertical lines (to the roundings of closest points: 1e-12 m).
    for (int i = 0; i < kGrid * kGrid; ++i) {
        const double x = (i % kGrid - 0.5 * (kGrid - 1)) * kSpacing, y = (i / kGrid - 0.5 * (kGrid - 1)) * kSpacing;
        EXPECT_NEAR(sim.state().shots.x[static_cast<std::size_t>(i)], x, 1e-12);
        EXPECT_NEAR(sim.state().shots.y[static_cast<std::size_t>(i)], y, 1e-12);
    }
    const double counted = kEngineEnd - kStart;
    for (ShotStats& s : stats) {
        s.floor_speed /= std::max(1.0, s.floor_rate);
        s.ceiling_speed /= std::max(1.0, s.ceiling_rate);
        s.floor_rate /= counted;
        s.ceiling_rate /= counted;
    }
    return stats;
}

std::vector<ShotStats> reference_statistics() {
    std::vector<ShotStats> stats;
    for (int i = 0; i < kGrid * kGrid; ++i) {
        VibratingFloorCase c{.R = kR, .g = kG, .A = kA, .F = kF, .phase = 0.0, .H = kH, .z0 = start_height(i),
                             .v0 = 0.0, .C0_floor = 0.9, .V0_floor = 1.5, .C0_ceiling = 0.95, .V0_ceiling = 2.0,
                             .duration = kReferenceEnd};
        c.statistics_start = kStart;
        const VibratingFloorStats r = simulate_vibrating_floor(c);
        stats.push_back({r.floor_rate(), r.floor.mean, r.ceiling_rate(), r.ceiling.mean});
    }
    return stats;
}

TEST(EngineVibratingFloor, RatesAndSpeedsMatchTheExactReference) {
    const std::vector<ShotStats> engine = engine_statistics();
    const std::vector<ShotStats> reference = reference_statistics();
    struct Quantity {
        const char* name;
        double ShotStats::*field;
    };
    const Quantity quantities[] = {{"floor rate (1/s)", &ShotStats::floor_rate},
                                   {"floor mean speed (m/s)", &ShotStats::floor_speed},
                                   {"ceiling rate (1/s)", &ShotStats::ceiling_rate},
                                   {"ceiling mean speed (m/s)", &ShotStats::ceiling_speed}};
    for (const Quantity& q : quantities) {
        const auto field = [&](const ShotStats& s) { return s.*(q.field); };
        const MeanAndError e = over_shots(engine, field), r = over_shots(reference, field);
        const double bound = 3.0 * std::hypot(e.standard_error, r.standard_error);
        std::cout << "[ vib floor] " << q.name << ": engine " << e.mean << " +- " << e.standard_error << ", reference "
                  << r.mean << " +- " << r.standard_error << "; difference " << (e.mean - r.mean) / r.mean * 100.0
                  << " %, bound (3 SE) " << bound / r.mean * 100.0 << " %\n";
        EXPECT_GT(e.mean, 0.0) << q.name;
        EXPECT_LE(std::abs(e.mean - r.mean), bound) << q.name;
    }
}

}  // namespace
}  // namespace peensim::testing
