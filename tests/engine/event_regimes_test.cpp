// Degenerate regimes an event-driven scheme can hang in or get wrong (the pitfalls of the reference
// notes, shared/reference/event-driven-notes.md), run with both stepping schemes (accuracy.scheme
// step and event). Each must finish its run (a Zeno sequence or a self-rescheduling event would
// hang it: no time is measured, the run simply has to end) with no serious health counter:
//  - chattering: one shot at rest on the vibrating sonotrode, at three plate phases, and the
//    bouncing-ball-on-a-table regime (A 25 um at 200 Hz: the plate's acceleration only 4 g);
//  - resting: shot dropped from rest on a still sonotrode come to rest on it (or on each other);
//  - dense load: 300 shot in a 20 x 20 mm chamber, several layers, sonotrode on;
//  - grazing: a shot flying exactly tangent over a box's top face and along the floor, a shot
//    sliding off a box's top face: no spurious impacts;
//  - a rotating part (1000 rpm): impact points on the part's surface in its own frame.
// Overlaps are audited (support/overlap_check.h: all pairs >= 2R - 1e-9 m, meshes >= R - 1e-9 m)
// at pauses (Simulation::step's pause_at_s; the time-stepping scheme ignores them and is audited at
// its step ends).
//
// Both schemes are held to finishing, health and each case's physics. The exactness claims are
// asserted for the event scheme only (`exact` below), and printed for both: no overlap beyond
// 1e-9 m, no impact logged for a touch at zero approach speed, impact points on a rotating part's
// surface to 1e-9 m. Time stepping does not claim them: it resolves shot pairs at step ends and
// corrects only overlaps above 1 % of R (docs/user-guide.md, "Outputs"), and moves a rotating part linearly within a step
// (EngineRotatingPart's bounds).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "engine/simulation.h"
#include "support/overlap_check.h"
#include "support/run_report.h"
#include "support/run_through_loop.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

constexpr double kG = 9.81;                       // m/s2
constexpr double kRegimeOverlapTolerance = 1e-9;  // m

class EngineEventRegimes : public ::testing::TestWithParam<std::string> {
protected:
    bool exact() const { return GetParam() == "event"; }
};

// Which regime of which scheme ran (the event scheme hands a restart interval over to time stepping
// when a load lies still): printed with every case, asserted where a case is about one regime.
std::string regime_text(const Simulation& sim) {
    const StepStats& st = sim.scheme().stats();
    return "regime: " + std::to_string(st.events) + " events, " + std::to_string(st.rides) + " rides, " + std::to_string(st.grazes) +
           " grazes, " + std::to_string(st.substeps) + " substeps, " + std::to_string(st.sleeps) + " sleeps, " +
           std::to_string(st.hand_overs) + " hand-overs to time stepping";
}

std::uint64_t impacts_on(const Model& model, const SimulationState& state, const std::string& component) {
    return state.impacts_per_component[static_cast<std::size_t>(model.component_index(component))];
}

// ---------------------------------------------------------------------------------------------
// a. Chattering

struct ChatterCase {
    const char* name;
    double amplitude_m;   // m
    double frequency_hz;  // Hz
    double phase_rad;     // rad, plate phase at t = 0
    double duration_s;    // s
    double min_height_m;  // m, the shot must be thrown higher than this above the plate's rest top
};

TEST_P(EngineEventRegimes, ChatteringShotOnTheVibratingSonotrodeIsThrown) {
    // The shot starts at rest exactly on the plate (centre R above the plate's top face where the
    // plate is at t = 0). Phase 0: the plate moves up through it at its peak speed (3.14 m/s);
    // pi/2: the plate is at its top, at rest, falling away faster than g; -pi/2: at its bottom, at
    // rest, accelerating up at 3.9e5 m/s2 (the shot rides it, then is launched). At 200 Hz the plate
    // accelerates at only 4 g and moves at 0.031 m/s at most: the shot is thrown a fraction of a
    // millimetre and keeps coming back at low speed, the regime of inelastic collapse (Zeno).
    const ChatterCase cases[] = {
        {"20 kHz phase 0", 25e-6, 20e3, 0.0, 0.05, 100e-6},
        {"20 kHz phase pi/2", 25e-6, 20e3, 0.5 * M_PI, 0.05, 100e-6},
        {"20 kHz phase -pi/2", 25e-6, 20e3, -0.5 * M_PI, 0.05, 100e-6},
        {"200 Hz phase 0", 25e-6, 200.0, 0.0, 0.5, 10e-6},
    };
    for (const ChatterCase& c : cases) {
        TestSceneSpec spec;
        spec.scheme = GetParam();
        spec.amplitude_m = c.amplitude_m;
        spec.frequency_hz = c.frequency_hz;
        spec.phase_rad = c.phase_rad;
        spec.duration_s = c.duration_s;
        spec.log = {"sonotrode", "chamber"};
        const TestScene scene(spec);
        const auto model = scene.compile();
        const auto t0 = std::chrono::steady_clock::now();
        Simulation sim(model);
        const double R = model->max_shot_radius_m;
        sim.edit_state(
            [&](SimulationState& edited) { set_shot(edited, 0, Vec3(0.0, 0.0, R + c.amplitude_m * std::sin(c.phase_rad)), Vec3::Zero()); });
        OverlapAudit audit(*model, kRegimeOverlapTolerance);
        std::size_t logged = 0;
        double max_height = 0.0;                     // m, centre above R over the plate's rest top face
        const double pause = 0.05 / c.frequency_hz;  // s, 20 audits a period
        run_through_loop(sim, {.after_step =
                                   [&](const Simulation&, const std::vector<ImpactRecord>& impacts) {
                                       logged += impacts.size();
                                       max_height = std::max(max_height, sim.state().shots.z[0] - R);
                                       audit.audit(sim.state());
                                   },
                               .pause_at_s = pause_every(pause)});
        const SimulationState& st = sim.state();
        std::cout << "[ chatter  ] " << GetParam() << " scheme, " << c.name << " (" << seconds_since(t0) << " s wall): " << st.steps
                  << " units, " << impacts_on(*model, st, "sonotrode") << " sonotrode and " << impacts_on(*model, st, "chamber")
                  << " chamber impacts, max height " << max_height << " m; " << audit.summary() << "; health " << health_text(st.health)
                  << "; " << regime_text(sim) << "\n";
        EXPECT_GT(max_height, c.min_height_m) << c.name;
        if (exact()) {
            // Event-driven throughout: a lone shot is never a load at rest to hand over.
            EXPECT_GT(sim.scheme().stats().events, 0u) << c.name;
            EXPECT_EQ(sim.scheme().stats().hand_overs, 0u) << c.name;
        }
        EXPECT_GT(impacts_on(*model, st, "sonotrode"), 0u) << c.name;
        EXPECT_EQ(logged, impacts_on(*model, st, "sonotrode") + impacts_on(*model, st, "chamber")) << c.name;
        if (exact()) {
            EXPECT_EQ(audit.report().mesh_overlaps, 0u) << c.name << ": " << audit.report().first_mesh;
        }
        EXPECT_EQ(st.health.serious(), 0u) << c.name << ": " << health_text(st.health);
    }
}

// ---------------------------------------------------------------------------------------------
// b. Resting

TEST_P(EngineEventRegimes, ShotDroppedOnTheStillSonotrodeComeToRest) {
    // 30 shot from rest (default coefficients: C0 0.9 below 0.5 m/s, f 0.1): 20 on a grid 0.5-2 mm
    // above the plate, 10 more 1-2 mm above ten of them (centres 3-4 mm apart) and 0.4 mm aside, so
    // that they hit those and scatter sideways. A bounce sequence from 6 mm (the highest start) at
    // C = 0.9 ends after 0.66 s, sliding at <~0.3 m/s stops within 0.03 s at f g: after 1 s every shot must be at rest
    // (speed < 1e-3 m/s) on the plate (centre R above it within 1e-6 m) or on another shot (touching
    // a lower one within 1e-6 m), and nothing overlaps (audited every ms).
    TestSceneSpec spec;
    spec.scheme = GetParam();
    spec.shot_count = 30;
    spec.duration_s = 1.0;
    spec.log = {"sonotrode"};
    const TestScene scene(spec);
    const auto model = scene.compile();
    const auto t0 = std::chrono::steady_clock::now();
    Simulation sim(model);
    const double R = model->max_shot_radius_m;
    for (int i = 0; i < 20; ++i) {
        const Vec3 p((i % 5 - 2) * 3.5e-3, (i / 5 - 1.5) * 3.5e-3, R + 0.5e-3 + 0.5e-3 * (i % 4));
        sim.edit_state([&](SimulationState& edited) { set_shot(edited, static_cast<std::size_t>(i), p, Vec3::Zero()); });
        if (i % 2 == 0) {
            const Vec3 above = p + Vec3(0.4e-3 * (i % 4 == 0 ? 1.0 : -1.0), 0.2e-3, 2.0 * R + 1e-3 + 0.5e-3 * (i % 3));
            sim.edit_state([&](SimulationState& edited) { set_shot(edited, static_cast<std::size_t>(20 + i / 2), above, Vec3::Zero()); });
        }
    }
    OverlapAudit audit(*model, kRegimeOverlapTolerance);
    audit.audit(sim.state());
    run_through_loop(sim, {.after_step = [&](const Simulation&, const std::vector<ImpactRecord>&) { audit.audit(sim.state()); },
                           .pause_at_s = pause_every(1e-3)});
    const SimulationState& st = sim.state();
    const ShotArrays& s = st.shots;
    int on_plate = 0, on_shot = 0;
    double fastest = 0.0, worst_plate = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        const double speed = s.velocity(i).norm();
        fastest = std::max(fastest, speed);
        EXPECT_LT(speed, 1e-3) << "shot " << i << " at " << s.position(i).transpose();
        if (std::abs(s.z[i] - R) < 1e-6) {
            ++on_plate;
            worst_plate = std::max(worst_plate, std::abs(s.z[i] - R));
            continue;
        }
        bool supported = false;
        for (std::size_t j = 0; j < s.size() && !supported; ++j)
            supported = j != i && s.z[j] < s.z[i] && std::abs((s.position(i) - s.position(j)).norm() - 2.0 * R) < 1e-6;
        on_shot += supported ? 1 : 0;
        EXPECT_TRUE(supported) << "shot " << i << " rests on nothing at " << s.position(i).transpose() << " m";
    }
    std::cout << "[ resting  ] " << GetParam() << " scheme (" << seconds_since(t0) << " s wall): " << st.steps << " units, "
              << impacts_on(*model, st, "sonotrode") << " sonotrode and " << st.shot_shot_impacts
              << " shot-shot impacts; at 1 s: " << on_plate << " on the plate (worst |z - R| " << worst_plate << " m), " << on_shot
              << " on another shot, fastest " << fastest << " m/s; " << audit.summary() << "; health " << health_text(st.health) << "; "
              << regime_text(sim) << "\n";
    if (exact()) {
        // Coming to rest is the sustained-contact regime: substeps, then sleep.
        EXPECT_GT(sim.scheme().stats().substeps, 0u);
    }
    EXPECT_GT(st.shot_shot_impacts, 0u);  // the upper shot did hit the lower ones
    if (exact()) {
        EXPECT_EQ(audit.report().pair_overlaps, 0u) << "first: " << audit.report().first_pair << "; deepest: " << audit.report().worst_pair;
        EXPECT_EQ(audit.report().mesh_overlaps, 0u) << "first: " << audit.report().first_mesh << "; deepest: " << audit.report().worst_mesh;
    }
    EXPECT_EQ(st.health.serious(), 0u) << health_text(st.health);
}

// ---------------------------------------------------------------------------------------------
// c. Dense load

TEST_P(EngineEventRegimes, DenseLoadOnTheVibratingSonotrode) {
    // 300 shot of 2 mm in a 20 x 20 mm chamber (2.4 times the floor area in shot cross-sections:
    // placed in layers on the plate), the sonotrode on (A 25 um, 20 kHz), 0.05 s, audited every
    // 50 us (one period).
    TestSceneSpec spec;
    spec.scheme = GetParam();
    spec.shot_count = 300;
    spec.amplitude_m = 25e-6;
    spec.duration_s = 0.05;
    spec.log = {"sonotrode"};
    const TestScene scene(spec);
    const auto model = scene.compile();
    const auto t0 = std::chrono::steady_clock::now();
    Simulation sim(model);
    double top = 0.0;
    for (std::size_t i = 0; i < sim.state().shots.size(); ++i) top = std::max(top, sim.state().shots.z[i]);
    OverlapAudit audit(*model, kRegimeOverlapTolerance);
    audit.audit(sim.state());
    run_through_loop(sim, {.after_step = [&](const Simulation&, const std::vector<ImpactRecord>&) { audit.audit(sim.state()); },
                           .pause_at_s = pause_every(50e-6)});
    const SimulationState& st = sim.state();
    std::cout << "[ dense    ] " << GetParam() << " scheme (" << seconds_since(t0) << " s wall): placed up to z = " << top << " m; "
              << st.steps << " units, " << impacts_on(*model, st, "sonotrode") << " sonotrode, " << impacts_on(*model, st, "chamber")
              << " chamber, " << st.shot_shot_impacts << " shot-shot impacts; " << audit.summary() << "; health " << health_text(st.health)
              << "; " << regime_text(sim) << "\n";
    if (!audit.report().first_pair.empty())
        std::cout << "[ dense    ] pair overlaps: first " << audit.report().first_pair << "; deepest " << audit.report().worst_pair << "\n";
    if (!audit.report().first_mesh.empty())
        std::cout << "[ dense    ] mesh overlaps: first " << audit.report().first_mesh << "; deepest " << audit.report().worst_mesh << "\n";
    EXPECT_GT(top, 4.0 * model->max_shot_radius_m);  // several layers
    EXPECT_GT(st.shot_shot_impacts, 2000u);          // a dense load: time stepping measured ~6000
    if (exact()) {
        EXPECT_EQ(audit.report().pair_overlaps, 0u) << audit.report().first_pair;
        EXPECT_EQ(audit.report().mesh_overlaps, 0u) << audit.report().first_mesh;
    }
    EXPECT_EQ(st.health.serious(), 0u) << health_text(st.health);
}

// ---------------------------------------------------------------------------------------------
// d. Grazing

// A 4 x 4 x 4 mm box part centred at (0, 0, 10 mm): top face z = 12 mm, x and y in [-2, 2] mm.
PartSpec grazing_box() {
    PartSpec box;
    box.shape = PartShape::box;
    box.size_m = Vec3(4e-3, 4e-3, 4e-3);
    box.center_m = Vec3(0.0, 0.0, 10e-3);
    return box;
}
constexpr double kBoxTop = 12e-3;  // m

TEST_P(EngineEventRegimes, GrazingFlightsWithoutGravityLogNoImpacts) {
    // No gravity, still sonotrode, 0.2 s. Shot 0 flies along x at 0.5 m/s with its centre exactly R
    // above the box's top face (y = 0): it passes over the face and its two edges touching them all
    // the way with zero normal speed, hits the +-x walls head on (tangential speed 0) and comes back
    // over the box again, ~5 times. Shot 1 flies along the plate (centre z = R, y = -6 mm) at
    // 0.3 m/s, touching it all the way. A touch at zero approach speed is no impact: no impact may
    // be logged on the box or the plate, and both flights must stay exactly on their lines.
    TestSceneSpec spec;
    spec.scheme = GetParam();
    spec.shot_count = 2;
    spec.gravity_m_per_s2 = Vec3::Zero();
    spec.duration_s = 0.2;
    spec.part = grazing_box();
    spec.log = {"part", "sonotrode", "chamber"};
    const TestScene scene(spec);
    const auto model = scene.compile();
    const auto t0 = std::chrono::steady_clock::now();
    Simulation sim(model);
    const double R = model->max_shot_radius_m;
    sim.edit_state([&](SimulationState& edited) { set_shot(edited, 0, Vec3(-8e-3, 0.0, kBoxTop + R), Vec3(0.5, 0.0, 0.0)); });
    sim.edit_state([&](SimulationState& edited) { set_shot(edited, 1, Vec3(-4e-3, -6e-3, R), Vec3(0.3, 0.0, 0.0)); });
    OverlapAudit audit(*model, kRegimeOverlapTolerance);
    double off_line = 0.0;  // m, largest departure of either shot from its line
    std::size_t box_passes = 0;
    bool over_box = false;
    std::string graze_impacts;  // every impact logged on the box or the plate, for the report
    run_through_loop(sim, {.after_step =
                               [&](const Simulation&, const std::vector<ImpactRecord>& impacts) {
                                   for (const ImpactRecord& r : impacts)
                                       if (r.component != model->component_index("chamber"))
                                           graze_impacts += " [t " + std::to_string(r.time_s) + " s, shot " + std::to_string(r.shot) +
                                                            ", " + model->components[static_cast<std::size_t>(r.component)].name +
                                                            ", vn_in " + std::to_string(r.vn_in_m_per_s) + " m/s]";
                                   const ShotArrays& s = sim.state().shots;
                                   off_line = std::max({off_line, std::abs(s.z[0] - (kBoxTop + R)), std::abs(s.y[0]), std::abs(s.z[1] - R),
                                                        std::abs(s.y[1] + 6e-3)});
                                   const bool over = std::abs(s.x[0]) < 2e-3;
                                   box_passes += over && !over_box;
                                   over_box = over;
                                   audit.audit(sim.state());
                               },
                           .pause_at_s = pause_every(1e-4)});
    const SimulationState& st = sim.state();
    std::cout << "[ grazing  ] " << GetParam() << " scheme, no gravity (" << seconds_since(t0) << " s wall): " << st.steps
              << " units; impacts: box " << impacts_on(*model, st, "part") << ", plate " << impacts_on(*model, st, "sonotrode")
              << ", walls " << impacts_on(*model, st, "chamber") << "; passes over the box seen " << box_passes
              << "; largest departure from the lines " << off_line << " m; final speeds " << st.shots.velocity(0).norm() << ", "
              << st.shots.velocity(1).norm() << " m/s; " << audit.summary() << "; health " << health_text(st.health) << "; "
              << regime_text(sim) << "\n";
    if (exact()) {
        // Flights exactly tangent to a face: grazes (no impact), all event-driven.
        EXPECT_GT(sim.scheme().stats().grazes, 0u);
        EXPECT_EQ(sim.scheme().stats().hand_overs, 0u);
    }
    if (!graze_impacts.empty()) std::cout << "[ grazing  ] logged on the box or plate:" << graze_impacts << "\n";
    if (exact()) {
        EXPECT_EQ(impacts_on(*model, st, "part"), 0u);
        EXPECT_EQ(impacts_on(*model, st, "sonotrode"), 0u);
        EXPECT_EQ(audit.report().mesh_overlaps, 0u) << audit.report().first_mesh;
    }
    EXPECT_GE(impacts_on(*model, st, "chamber"), 4u);  // both shot bounced off the walls
    EXPECT_GE(box_passes, 3u);
    EXPECT_LT(off_line, 1e-12);
    EXPECT_EQ(st.shot_shot_impacts, 0u);
    EXPECT_EQ(st.health.serious(), 0u) << health_text(st.health);
}

TEST_P(EngineEventRegimes, ShotSlidingOnTheFloorAndOffABoxTopLogNoSpuriousImpacts) {
    // Gravity on, still sonotrode, 0.15 s. Shot 0 rests on the plate (centre z = R, y = -6 mm)
    // sliding at 0.1 m/s along x: friction (f 0.1) stops it after 0.102 s and 5.1 mm, without a
    // single impact, its centre staying R above the plate (1e-9 m, as EngineRest). Shot 1 rests on
    // the box's top face (centre z = 12 mm + R) sliding at 0.2 m/s towards +x from x = -1.5 mm: it
    // crosses the face (and the diagonal edge its two triangles share) and leaves the edge at
    // 0.18 m/s, faster than sqrt(g R) = 0.099 m/s, so it flies off clear of the edge, hits the +x
    // wall on its way down and lands on the plate: no impact on the box's top face or its edges
    // (points at z = 12 mm in the box's frame). (Bouncing on the plate afterwards it may hit the
    // box's side face, a real impact; it can no longer reach the top: it fell from it.)
    TestSceneSpec spec;
    spec.scheme = GetParam();
    spec.shot_count = 2;
    spec.duration_s = 0.15;
    spec.part = grazing_box();
    spec.log = {"part", "sonotrode", "chamber"};
    const TestScene scene(spec);
    const auto model = scene.compile();
    const auto t0 = std::chrono::steady_clock::now();
    Simulation sim(model);
    const double R = model->max_shot_radius_m;
    const double f = spec.sonotrode.f;
    const Vec3 start0(-4e-3, -6e-3, R);
    sim.edit_state([&](SimulationState& edited) { set_shot(edited, 0, start0, Vec3(0.1, 0.0, 0.0)); });
    sim.edit_state([&](SimulationState& edited) { set_shot(edited, 1, Vec3(-1.5e-3, 0.0, kBoxTop + R), Vec3(0.2, 0.0, 0.0)); });
    OverlapAudit audit(*model, kRegimeOverlapTolerance);
    std::size_t floor_impacts_of_0 = 0, box_top_impacts = 0;
    double sink = 0.0;  // m, largest |z - R| of shot 0
    const int part = model->component_index("part");
    run_through_loop(sim, {.after_step =
                               [&](const Simulation&, const std::vector<ImpactRecord>& impacts) {
                                   for (const ImpactRecord& r : impacts) {
                                       floor_impacts_of_0 += r.shot == 0;
                                       box_top_impacts += r.component == part && r.point_m.z() > kBoxTop - 1e-9;
                                   }
                                   sink = std::max(sink, std::abs(sim.state().shots.z[0] - R));
                                   audit.audit(sim.state());
                               },
                           .pause_at_s = pause_every(1e-4)});
    const SimulationState& st = sim.state();
    const ShotArrays& s = st.shots;
    const double slid = s.x[0] - start0.x(), expected = 0.1 * 0.1 / (2.0 * f * kG);
    std::cout << "[ grazing  ] " << GetParam() << " scheme, gravity (" << seconds_since(t0) << " s wall): " << st.steps
              << " units; impacts: box " << impacts_on(*model, st, "part") << " (on its top " << box_top_impacts << "), plate "
              << impacts_on(*model, st, "sonotrode") << ", walls " << impacts_on(*model, st, "chamber")
              << "; sliding shot: " << floor_impacts_of_0 << " impacts, slid " << slid << " m (v0^2 / 2 f g = " << expected
              << " m), worst |z - R| " << sink << " m, final speed " << s.velocity(0).norm() << " m/s; shot off the box ends at "
              << s.position(1).transpose() << " m; " << audit.summary() << "; health " << health_text(st.health) << "\n";
    EXPECT_EQ(box_top_impacts, 0u);
    EXPECT_EQ(floor_impacts_of_0, 0u);
    EXPECT_LT(sink, 1e-9);
    EXPECT_LT(s.velocity(0).norm(), 1e-3);
    EXPECT_LT(s.z[1], kBoxTop - 4e-3);                 // it left the box top and fell below the box's bottom face
    EXPECT_GT(impacts_on(*model, st, "chamber"), 0u);  // on the +x wall
    if (exact()) {
        EXPECT_EQ(audit.report().mesh_overlaps, 0u) << "first: " << audit.report().first_mesh << "; deepest: " << audit.report().worst_mesh;
    }
    EXPECT_EQ(st.health.serious(), 0u) << health_text(st.health);
}

// ---------------------------------------------------------------------------------------------
// e. Rotating part

TEST_P(EngineEventRegimes, RotatingPartImpactsLieOnItsSurface) {
    // A 10 x 6 x 2 mm plate part centred 10 mm above the sonotrode, turning at 1000 rpm about +y
    // through its centre (rim speed 0.53 m/s; it sweeps down to 4.9 mm), 64 shot thrown at 1 m/s
    // and by the 25 um sonotrode, 0.1 s, audited every 50 us. Every logged part impact's point (part
    // frame) must lie on the part's mesh within 1e-9 m.
    constexpr double omega = 1000.0 * 2.0 * M_PI / 60.0;  // rad/s
    TestSceneSpec spec;
    spec.scheme = GetParam();
    spec.shot_count = 64;
    spec.initial_speed_m_per_s = 1.0;
    spec.amplitude_m = 25e-6;
    spec.duration_s = 0.1;
    spec.part = turning_plate_part(omega);
    spec.log = {"part"};
    const TestScene scene(spec);
    const auto model = scene.compile();
    const Component& rotor = model->components[static_cast<std::size_t>(model->component_index("part"))];
    const auto t0 = std::chrono::steady_clock::now();
    Simulation sim(model);
    OverlapAudit audit(*model, kRegimeOverlapTolerance);
    std::size_t logged = 0, off_surface = 0;
    double worst_distance = 0.0;  // m, farthest logged point from the part's mesh
    run_through_loop(sim, {.after_step =
                               [&](const Simulation&, const std::vector<ImpactRecord>& impacts) {
                                   for (const ImpactRecord& r : impacts) {
                                       ++logged;
                                       MeshCollider::Closest closest;
                                       MeshCollider::QueryCounters counters;
                                       const double d =
                                           rotor.collider->closest_within(r.point_m, 1e-3, closest, counters) ? closest.distance : 1e-3;
                                       worst_distance = std::max(worst_distance, d);
                                       off_surface += d >= 1e-9;
                                   }
                                   audit.audit(sim.state());
                               },
                           .pause_at_s = pause_every(50e-6)});
    const SimulationState& st = sim.state();
    std::cout << "[ rotating ] " << GetParam() << " scheme, 1000 rpm (" << seconds_since(t0) << " s wall): " << st.steps << " units, "
              << logged << " part impacts, farthest point from the part surface " << worst_distance << " m (" << off_surface
              << " beyond 1e-9 m); " << st.shot_shot_impacts << " shot-shot impacts; " << audit.summary() << "; health "
              << health_text(st.health) << "\n";
    EXPECT_GT(logged, 50u);
    EXPECT_EQ(logged, impacts_on(*model, st, "part"));
    EXPECT_EQ(st.health.shot_lost, 0u);
    if (exact()) {
        EXPECT_EQ(off_surface, 0u) << "worst " << worst_distance << " m";
        EXPECT_EQ(audit.report().pair_overlaps, 0u) << audit.report().first_pair;
        EXPECT_EQ(audit.report().mesh_overlaps, 0u) << audit.report().first_mesh;
    }
    EXPECT_EQ(st.health.serious(), 0u) << health_text(st.health);
}

INSTANTIATE_TEST_SUITE_P(Schemes, EngineEventRegimes, ::testing::Values(std::string("step"), std::string("event")),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace peensim::testing
