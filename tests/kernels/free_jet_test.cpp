// The nozzle's air jet (kernels/free_jet.h) and flights through it (kernels/air_drag_flight.h): the
// field against its formulas (the potential core, then the self-similar jet); a shot let go on the axis of the jet's core, accelerated by
// quadratic drag towards the air's speed, against the closed form; the speed-gain bound; and the jet in a run of the nozzle study: the shot
// arrive faster than they left when the air is faster.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "engine/run_loop.h"
#include "engine/simulation.h"
#include "kernels/air_drag_flight.h"
#include "kernels/free_jet.h"
#include "model/model.h"
#include "model/shot_flow.h"
#include "scene/scene_parser.h"
#include "support/run_through_loop.h"

namespace peensim {
namespace {

FreeJet jet_down(double diameter_m, double speed_m_per_s) {
    FreeJet j;
    j.exit_m = Vec3(0.0, 0.0, 0.05);
    j.axis = -Vec3::UnitZ();
    j.exit_diameter_m = diameter_m;
    j.exit_speed_m_per_s = speed_m_per_s;
    return j;
}

TEST(FreeJet, FieldKeepsItsPotentialCoreThenTurnsSelfSimilar) {
    const FreeJet j = jet_down(6e-3, 150.0);
    const Vec3 down = -Vec3::UnitZ();
    const auto at = [&](double s, double r) { return j.velocity_at(j.exit_m + s * down + r * Vec3::UnitX()); };
    const double ln2 = std::log(2.0), sc = 5.8 * 6e-3;  // -, m: the core's length 34.8 mm
    // The core: U_0 out to r_c = 3 mm (1 - s / s_c); at the exit the nozzle's top hat.
    EXPECT_EQ(at(1e-6, 2.99e-3), 150.0 * down);
    EXPECT_NEAR(at(1e-6, 3.01e-3).z(), 0.0, 1e-12);
    EXPECT_EQ(at(1e-3, 0.0), 150.0 * down);
    EXPECT_EQ(at(1e-3, 1.9e-3), 150.0 * down);      // by the nozzle wall: was 0.76 U_0 (a Gaussian from the exit)
    const double rc10 = 3e-3 * (1.0 - 10e-3 / sc);  // m, the core's radius at s = 10 mm
    EXPECT_EQ(at(10e-3, rc10 * 0.999), 150.0 * down);
    // Its mixing layer: half of U_0 one half-width b = 0.094 s beyond the core.
    EXPECT_NEAR(at(10e-3, rc10 + 0.094 * 10e-3).z(), -75.0, 1e-12);
    EXPECT_NEAR(at(10e-3, rc10 + 0.5e-3).z(), -150.0 * std::exp(-ln2 * std::pow(0.5e-3 / 0.94e-3, 2)), 1e-12);
    // Where the core closes the two forms are one: continuous across s_c, on and off the axis.
    for (double r : {0.0, 1e-3, 3e-3, 6e-3}) EXPECT_NEAR(at(sc * (1.0 - 1e-12), r).z(), at(sc * (1.0 + 1e-12), r).z(), 1e-8) << "r " << r;
    // Beyond: U_0 5.8 D_n / s on the axis (twice the core's length: half), half-width 0.094 s.
    EXPECT_NEAR(at(69.6e-3, 0.0).z(), -75.0, 1e-12);
    EXPECT_NEAR(at(69.6e-3, 0.094 * 69.6e-3).z(), -37.5, 1e-12);
    // Upstream of the exit: still air; and along the axis only.
    EXPECT_EQ(at(-1e-3, 0.0), Vec3::Zero());
    EXPECT_EQ(at(20e-3, 1e-3).x(), 0.0);
    // Two jets add.
    const AirVelocityField two({j, j});
    EXPECT_NEAR(two.at(j.exit_m + 5e-3 * down).z(), -300.0, 1e-12);
    EXPECT_EQ(two.max_speed(), 300.0);
}

// A 0.58 mm steel shot let go at rest on the axis, 1 mm below the exit, with constant C_d and no
// gravity: in the core the air moves at U_0, so w = U_0 - v obeys w' = -k w^2:
// v(t) = U_0 - U_0 / (1 + k U_0 t), s(t) = U_0 t - ln(1 + k U_0 t) / k.
TEST(FreeJet, AShotInTheCoreIsBlownAsTheClosedFormSays) {
    AirDrag air;
    air.shot_radius_m = 0.29e-3;
    air.shot_density_kg_per_m3 = 7800.0;
    air.drag_coefficient = 0.44;
    const FreeJet j = jet_down(6e-3, 100.0);
    air.wind = std::make_shared<const AirVelocityField>(std::vector<FreeJet>{j});
    const AirDragFlight flight(Vec3::Zero(), air);
    const double k = 3.0 * 1.205 * 0.44 / (8.0 * 7800.0 * 0.29e-3), U = 100.0;
    Vec3 p = j.exit_m - 1e-3 * Vec3::UnitZ(), v = Vec3::Zero();
    const Vec3 start = p;
    const double dt = 1e-5, t = 8e-3;  // 800 steps; 27 mm down, inside the 34.8 mm core
    for (int n = 0; n < 800; ++n) flight.advance(p, v, dt);
    const double v_exact = U - U / (1.0 + k * U * t), s_exact = U * t - std::log1p(k * U * t) / k;
    EXPECT_GT(s_exact, 0.02);
    EXPECT_NEAR(-v.z(), v_exact, 1e-6 * v_exact);
    EXPECT_NEAR(start.z() - p.z(), s_exact, 1e-6 * s_exact);
    EXPECT_EQ(p.x(), start.x());
    EXPECT_EQ(v.x(), 0.0);
}

TEST(FreeJet, SpeedNeverGrowsFasterThanTheBound) {
    AirDrag air;
    air.shot_radius_m = 0.29e-3;
    air.shot_density_kg_per_m3 = 7800.0;
    const FreeJet j = jet_down(6e-3, 200.0);
    air.wind = std::make_shared<const AirVelocityField>(std::vector<FreeJet>{j});
    const AirDragFlight flight(Vec3(0, 0, -9.81), air);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    double closest = 0.0;
    for (int n = 0; n < 20000; ++n) {
        const Vec3 p = j.exit_m + Vec3(4e-3 * u(rng), 4e-3 * u(rng), -0.04 * (u(rng) + 1.0));
        const Vec3 v = 250.0 * Vec3(u(rng), u(rng), u(rng));
        if (v.norm() < 1e-9) continue;
        const double gain = flight.acceleration(p, v).dot(v.normalized());
        EXPECT_LE(gain, flight.speed_gain_bound());
        closest = std::max(closest, gain / flight.speed_gain_bound());
    }
    EXPECT_GT(closest, 0.05);  // the bound is not absurdly loose where the jet is strong
}

// The study's nozzle with drag: in still air the first shot loses 0.2 % of its speed over the 20
// mm; a 150 m/s air jet takes most of that loss away (the air outruns the 100 m/s shot where it is
// faster than it, near the axis; off it the profile falls to half at the exit radius).
TEST(FreeJet, TheJetSpeedsUpTheStudysShot) {
    const std::string scene = std::string(PEENSIM_SOURCE_DIR) + "/scenes/nozzle-study.yaml";
    const auto first_impact_over_exit = [&](const std::vector<std::string>& extra) {
        std::vector<std::string> set{"process.duration=1 ms", "air.drag=sphere", "accuracy.scheme=step"};
        set.insert(set.end(), extra.begin(), extra.end());
        const auto model = compile_model(parse_scene_file(scene, set));
        Simulation sim(model);
        // The impacts of the first step that logged any (time stepping: every step is a restart
        // point, so the run ends right after it).
        std::vector<ImpactRecord> impacts;
        testing::run_through_loop(sim, {.after_step =
                                            [&](const Simulation&, const std::vector<ImpactRecord>& step) {
                                                if (impacts.empty()) impacts = step;
                                            },
                                        .done = [&](const Simulation&) { return !impacts.empty(); }});
        EXPECT_FALSE(impacts.empty());
        const Emission e = *model->sources[0]->emission(0);
        for (const ImpactRecord& i : impacts)
            if (i.shot == 0) return i.vn_in_m_per_s / e.velocity_m_per_s.norm();
        return 0.0;
    };
    const double still = first_impact_over_exit({}), blown = first_impact_over_exit({"sources[nozzle].air_speed=150 m/s"});
    std::cout << "[ jet      ] first impact over exit speed: still air " << still << ", 150 m/s jet " << blown << "\n";
    EXPECT_LT(still, 1.0);
    EXPECT_GT(still, 0.99);
    EXPECT_GT(blown, still + 0.001);
}

}  // namespace
}  // namespace peensim
