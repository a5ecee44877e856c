// Flight models (kernels/flight_model.h): the parabola is eq. 1 exactly; air drag against the
// closed-form flights of quadratic drag at a constant C_d (horizontal without gravity, vertical
// fall from rest), its drag coefficient's exact values, its speed bound; and a shot dropped in a
// scene with drag lands when and as fast as the closed form says (time stepping; the event scheme
// is refused for drag).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "engine/simulation.h"
#include "kernels/air_drag_flight.h"
#include "kernels/trajectory.h"
#include "support/run_through_loop.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

constexpr double kR = 0.5e-3;            // m, a 1 mm shot
constexpr double kShotDensity = 7800.0;  // kg/m3, steel

AirDrag steel_shot_in_air(std::optional<double> cd = std::nullopt) {
    AirDrag air;
    air.shot_radius_m = kR;
    air.shot_density_kg_per_m3 = kShotDensity;
    air.drag_coefficient = cd;
    return air;
}

// 1/m, k of a = -k |v| v at constant C_d.
double k_of(const AirDrag& air, double cd) {
    return 3.0 * air.air_density_kg_per_m3 * cd / (8.0 * air.shot_density_kg_per_m3 * air.shot_radius_m);
}

TEST(ParabolaFlight, IsEquationOneExactly) {
    const Vec3 g(0.0, 0.0, -9.81);
    const ParabolaFlight flight(g);
    Vec3 p(1e-3, 2e-3, 3e-3), v(0.3, -0.2, 1.1);
    const Trajectory path{p, v, g, 0.0};
    flight.advance(p, v, 0.0123);
    EXPECT_EQ(p, path.position(0.0123));
    EXPECT_EQ(v, path.velocity(0.0123));
    EXPECT_TRUE(flight.is_parabola());
    EXPECT_EQ(flight.speed_gain_bound(), 9.81);
}

// The standard drag curve (Clift, Grace & Weber 1978, Table 5.2), piece by piece: its exact values,
// its pieces meeting, the Stokes limit, and two independent references: Schiller-Naumann where it
// holds (Re < 800, stated to within 5 % of the curve) and the drag force growing with the speed
// (the speed-gain bound of time stepping relies on it).
TEST(AirDragFlight, DragCoefficientIsTheStandardDragCurve) {
    const AirDragFlight flight(Vec3::Zero(), steel_shot_in_air());
    const auto w = [](double re) { return std::log10(re); };
    EXPECT_DOUBLE_EQ(flight.drag_coefficient(0.005), 3.0 / 16.0 + 24.0 / 0.005);
    EXPECT_DOUBLE_EQ(flight.drag_coefficient(1.0), 24.0 * (1.0 + 0.1315));
    EXPECT_DOUBLE_EQ(flight.drag_coefficient(100.0), 0.24 * (1.0 + 0.1935 * std::pow(100.0, 0.6305)));
    EXPECT_DOUBLE_EQ(flight.drag_coefficient(1000.0), std::pow(10.0, 1.6435 - 1.1242 * 3.0 + 0.1558 * 9.0));
    // (to rounding: the code forms the powers of w by products)
    EXPECT_NEAR(flight.drag_coefficient(5000.0),
                std::pow(10.0, -2.4571 + 2.5558 * w(5000.0) - 0.9295 * std::pow(w(5000.0), 2) + 0.1049 * std::pow(w(5000.0), 3)), 1e-14);
    EXPECT_NEAR(flight.drag_coefficient(2e4), std::pow(10.0, -1.9181 + 0.6370 * w(2e4) - 0.0636 * std::pow(w(2e4), 2)), 1e-14);
    EXPECT_NEAR(flight.drag_coefficient(1e5), std::pow(10.0, -4.3390 + 1.5809 * 5.0 - 0.1546 * 25.0), 1e-14);
    // Held from the drag crisis on.
    EXPECT_EQ(flight.drag_coefficient(1e6), flight.drag_coefficient(3.38e5));
    // Where the pieces meet, within 0.8 %.
    for (double re : {0.01, 20.0, 260.0, 1.5e3, 1.2e4, 4.4e4})
        EXPECT_NEAR(flight.drag_coefficient(re * (1.0 + 1e-12)) / flight.drag_coefficient(re), 1.0, 8e-3) << "Re " << re;
    // Stokes: 24 / Re as Re -> 0.
    EXPECT_NEAR(flight.drag_coefficient(1e-4) * 1e-4 / 24.0, 1.0, 1e-5);
    // Schiller-Naumann, 24/Re (1 + 0.15 Re^0.687), within 5 % of the curve up to Re 800.
    for (double re = 0.1; re <= 800.0; re *= 1.1)
        EXPECT_NEAR(flight.drag_coefficient(re) / (24.0 / re * (1.0 + 0.15 * std::pow(re, 0.687))), 1.0, 0.05) << "Re " << re;
    // The drag force, C_d Re^2, grows with the speed over every Re a shot can meet and beyond.
    double last = 0.0;
    for (double re = 1e-3; re <= 1e7; re *= 1.01) {
        const double force = flight.drag_coefficient(re) * re * re;
        ASSERT_GT(force, last) << "Re " << re;
        last = force;
    }
    // Re = rho v D / mu: 1 mm at 10 m/s in air at 20 C.
    EXPECT_DOUBLE_EQ(flight.reynolds(10.0), 1.205 * 10.0 * 1e-3 / 1.822e-5);
    // A constant coefficient replaces the curve.
    EXPECT_EQ(AirDragFlight(Vec3::Zero(), steel_shot_in_air(0.47)).drag_coefficient(3.0), 0.47);
}

TEST(AirDragFlight, AccelerationIsGravityMinusDragAlongTheVelocity) {
    const Vec3 g(0.0, 0.0, -9.81);
    const AirDrag air = steel_shot_in_air(0.44);
    const AirDragFlight flight(g, air);
    const Vec3 v(30.0, 0.0, -40.0);  // |v| = 50 m/s
    const Vec3 a = flight.acceleration(Vec3::Zero(), v);
    const Vec3 expected = g - k_of(air, 0.44) * 50.0 * v;
    EXPECT_NEAR((a - expected).norm(), 0.0, 1e-12 * expected.norm());
    EXPECT_EQ(flight.acceleration(Vec3::Zero(), Vec3::Zero()), g);  // at rest: gravity alone, no 0/0
}

// Without gravity, quadratic drag at constant C_d: v(t) = v0 / (1 + k v0 t), x(t) = ln(1 + k v0 t) / k.
TEST(AirDragFlight, HorizontalFlightMatchesTheClosedForm) {
    const AirDrag air = steel_shot_in_air(0.44);
    const AirDragFlight flight(Vec3::Zero(), air);
    const double k = k_of(air, 0.44), v0 = 80.0;  // m/s, a conventional jet
    // Time stepping's step at this speed: a quarter radius of travel.
    const double dt = 0.25 * kR / v0;
    Vec3 p = Vec3::Zero(), v(v0, 0.0, 0.0);
    const int steps = 40000;  // 0.0625 s, 3.4 m of flight: the shot loses 20 % of its speed
    for (int s = 0; s < steps; ++s) flight.advance(p, v, dt);
    const double t = steps * dt;
    const double v_exact = v0 / (1.0 + k * v0 * t), x_exact = std::log1p(k * v0 * t) / k;
    EXPECT_LT(v_exact, 0.85 * v0);           // the drag is felt
    EXPECT_NEAR(v.x(), v_exact, 1e-9 * v0);  // measured: 5e-15 of v0 (distance 1.2e-14 of itself)
    EXPECT_NEAR(p.x(), x_exact, 1e-9 * x_exact);
    EXPECT_EQ(p.y(), 0.0);
    EXPECT_EQ(v.z(), 0.0);
}

// Falling from rest at constant C_d: v(t) = vt tanh(g t / vt), depth vt^2 / g ln cosh(g t / vt),
// vt = sqrt(g / k) the terminal speed.
TEST(AirDragFlight, FallFromRestReachesTheTerminalSpeed) {
    const double g = 9.81;
    const AirDrag air = steel_shot_in_air(0.44);
    const AirDragFlight flight(Vec3(0.0, 0.0, -g), air);
    const double vt = std::sqrt(g / k_of(air, 0.44));  // ~20 m/s for 1 mm steel
    Vec3 p = Vec3::Zero(), v = Vec3::Zero();
    const double dt = 1e-5;
    const int steps = 400000;  // 4 s
    double worst_speed = 0.0;
    for (int s = 1; s <= steps; ++s) {
        flight.advance(p, v, dt);
        const double t = s * dt;
        worst_speed = std::max(worst_speed, std::abs(-v.z() - vt * std::tanh(g * t / vt)));
    }
    const double t = steps * dt;
    EXPECT_LT(worst_speed, 1e-9 * vt);  // measured: 2.4e-14 of vt (depth 2.2e-15 of itself), at 99.3 % of vt
    EXPECT_NEAR(-p.z(), vt * vt / g * std::log(std::cosh(g * t / vt)), 1e-9 * -p.z());
    EXPECT_GT(-v.z(), 0.9 * vt);
}

// With C_d(Re) there is no closed form: the steps time stepping takes agree with steps 64 times
// shorter (the converged flight) far below a nanometre.
TEST(AirDragFlight, StandardCurveFlightConvergesAtTimeSteppingsSteps) {
    const AirDragFlight flight(Vec3(0.0, 0.0, -9.81), steel_shot_in_air());
    const Vec3 v0(20.0, 0.0, 5.0);
    const double dt = 0.25 * kR / v0.norm();
    Vec3 p = Vec3::Zero(), v = v0, p_fine = p, v_fine = v;
    for (int s = 0; s < 2000; ++s) {
        flight.advance(p, v, dt);
        for (int f = 0; f < 64; ++f) flight.advance(p_fine, v_fine, dt / 64.0);
    }
    EXPECT_LT((v - v0).norm(), 0.5);  // drag and gravity changed the velocity over the flight
    EXPECT_GT((v - v0).norm(), 0.01);
    EXPECT_LT((p - p_fine).norm(), 1e-12);  // measured: 1.0e-15 m
    EXPECT_LT((v - v_fine).norm(), 1e-10);  // measured: 2.2e-13 m/s
}

// Still air only slows a shot: along its velocity the acceleration never exceeds |g|, the bound
// time stepping sizes its steps by.
TEST(AirDragFlight, SpeedNeverGrowsFasterThanGravity) {
    const Vec3 g(0.0, -3.0, -9.0);
    const AirDragFlight flight(g, steel_shot_in_air());
    std::mt19937_64 rng(7);
    std::normal_distribution<double> normal(0.0, 10.0);
    for (int k = 0; k < 1000; ++k) {
        const Vec3 v(normal(rng), normal(rng), normal(rng));
        EXPECT_LE(flight.acceleration(Vec3::Zero(), v).dot(v.normalized()), flight.speed_gain_bound() * (1.0 + 1e-15));
    }
}

// A 2 mm shot dropped 30 mm onto the still plate through dense air (50 kg/m3, C_d 0.44: terminal
// speed 3 m/s): it lands at v = vt sqrt(1 - exp(-2 g h / vt^2)), at t = vt / g acosh(exp(g h / vt^2)),
// 1 % slower and later than in vacuum.
TEST(AirDragFlight, ShotDroppedThroughAirLandsAsTheClosedFormSays) {
    TestSceneSpec spec;
    spec.chamber_size_m = Vec3(20e-3, 20e-3, 40e-3);
    spec.sonotrode = {0.5, 1e3, 0.71, 0.1};
    spec.log = {"sonotrode"};
    spec.duration_s = 0.1;
    const TestScene scene(spec);
    const auto model = scene.compile({"air.drag=sphere", "air.density=50 kg/m3", "air.drag_coefficient=0.44"});
    ASSERT_FALSE(model->flight->is_parabola());
    EXPECT_EQ(model->scheme, SteppingScheme::step);
    const double R = model->max_shot_radius_m, h = 30e-3, g = 9.81;
    Simulation sim(model);
    sim.edit_state([&](SimulationState& s) { set_shot(s, 0, Vec3(0.0, 0.0, R + h), Vec3::Zero()); });
    // Time stepping (asserted above): every step is a restart point, so the run ends right after
    // the step that logged the first impact.
    std::vector<ImpactRecord> impacts;
    run_through_loop(sim,
                     {.after_step = [&](const Simulation&,
                                        const std::vector<ImpactRecord>& step) { impacts.insert(impacts.end(), step.begin(), step.end()); },
                      .done = [&](const Simulation&) { return !impacts.empty(); }});
    ASSERT_FALSE(impacts.empty());
    const double k = 3.0 * 50.0 * 0.44 / (8.0 * 7800.0 * R), vt = std::sqrt(g / k);
    const double v_land = vt * std::sqrt(1.0 - std::exp(-2.0 * g * h / (vt * vt)));
    const double t_land = vt / g * std::acosh(std::exp(g * h / (vt * vt)));
    EXPECT_LT(v_land, 0.995 * std::sqrt(2.0 * g * h));  // drag is felt
    // Measured: both within 6e-10 of themselves (the touch time is found on the step's arc).
    EXPECT_NEAR(impacts.front().vn_in_m_per_s, v_land, 5e-9 * v_land);
    EXPECT_NEAR(impacts.front().time_s, t_land, 5e-9 * t_land);
}

}  // namespace
}  // namespace peensim::testing
