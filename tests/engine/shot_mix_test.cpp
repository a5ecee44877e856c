// Shot size mixes (shot.sizes): the mix's arithmetic (count shares from mass shares, the mean
// mass a mass flow divides by, the draw); what the scene accepts and refuses; the sizes each shot
// draws (placed and emitted: their frequencies, reproducible, a redraw keeps its size, a scene of
// one size draws nothing); an exact collision of two sizes in both rigid schemes (contact at
// R_i + R_j, momentum and restitution weighed by mass); a mix in a USP chamber and in the
// nozzle's jet (no overlaps, healthy, every size logged with its diameter); and a resumed run of
// the shipped mix scene equal to the uninterrupted one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "common/input_error.h"
#include "contact/restitution.h"
#include "engine/run_loop.h"
#include "engine/simulation.h"
#include "model/model.h"
#include "model/shot_placement.h"
#include "output/impact_csv_writer.h"
#include "scene/resolved_writer.h"
#include "scene/scene_parser.h"
#include "scene/shot_mix.h"
#include "support/files.h"
#include "support/overlap_check.h"
#include "support/run_in_process.h"
#include "support/run_through_loop.h"
#include "support/temp_dir.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

const std::string kMixScene = std::string(PEENSIM_SOURCE_DIR) + "/scenes/nozzle-mix.yaml";
const std::string kStudyScene = std::string(PEENSIM_SOURCE_DIR) + "/scenes/nozzle-study.yaml";

ShotDesc mix_by_mass() {
    ShotDesc d;
    d.density_kg_per_m3 = 7800.0;
    d.fractions_by_mass = true;
    d.sizes = {{1e-3, 0.5}, {0.5e-3, 0.5}};  // half the mass in 1 mm shot, half in 0.5 mm
    return d;
}

TEST(ShotMix, CountSharesFromMassSharesAndTheMeanMass) {
    // Equal masses of 1 mm and 0.5 mm shot: a 1 mm shot weighs 8 of the others, so there are 8
    // small ones to each large one: count shares 1/9 and 8/9.
    ShotDesc d = mix_by_mass();
    const std::vector<double> share = count_fractions(d);
    EXPECT_DOUBLE_EQ(share[0], 1.0 / 9.0);
    EXPECT_DOUBLE_EQ(share[1], 8.0 / 9.0);
    // The mean shot: (1 m1 + 8 m1 / 8) / 9 = 2 m1 / 9; a mass flow of M kg/s is 4.5 M / m1 shot/s.
    const double m1 = sphere_mass_kg(1e-3, 7800.0);
    EXPECT_NEAR(m1, 7800.0 * M_PI / 6.0 * 1e-9, 1e-20);
    EXPECT_DOUBLE_EQ(mean_shot_mass_kg(d), 2.0 * m1 / 9.0);
    // By count the shares are the fractions themselves.
    d.fractions_by_mass = false;
    EXPECT_EQ(count_fractions(d), (std::vector<double>{0.5, 0.5}));
    EXPECT_DOUBLE_EQ(mean_shot_mass_kg(d), 0.5 * m1 + 0.5 * m1 / 8.0);
    EXPECT_EQ(largest_diameter_m(d), 1e-3);
    EXPECT_EQ(smallest_diameter_m(d), 0.5e-3);
    // The draw: the first size whose cumulative share exceeds u; the last for u at the sum.
    const std::vector<double> f{0.25, 0.5, 0.25};
    EXPECT_EQ(size_for_draw(f, 0.0), 0);
    EXPECT_EQ(size_for_draw(f, 0.2499), 0);
    EXPECT_EQ(size_for_draw(f, 0.25), 1);
    EXPECT_EQ(size_for_draw(f, 0.7499), 1);
    EXPECT_EQ(size_for_draw(f, 0.75), 2);
    EXPECT_EQ(size_for_draw(f, 1.0), 2);
    EXPECT_EQ(size_for_draw(std::vector<double>{1.0}, 0.999), 0);
}

TEST(ShotMix, TheSceneReadsAMixAndItsMassFlow) {
    const SceneDescription s = parse_scene_file(kMixScene);
    ASSERT_EQ(s.shot.sizes.size(), 4u);
    EXPECT_TRUE(s.shot.sizes_given);
    EXPECT_TRUE(s.shot.fractions_by_mass);
    EXPECT_DOUBLE_EQ(s.shot.sizes[0].diameter_m, 0.71e-3);
    EXPECT_DOUBLE_EQ(s.shot.sizes[3].fraction, 0.1);
    // 5.5 kg/min over the mix's mean mass.
    EXPECT_DOUBLE_EQ(s.sources[0].rate_per_s, 5.5 / 60.0 / mean_shot_mass_kg(s.shot));
    // The model: radii, masses, count shares (summing to 1), the extremes.
    const auto model = compile_model(s);
    ASSERT_EQ(model->shot_sizes.size(), 4u);
    EXPECT_TRUE(model->has_size_mix());
    double sum = 0.0;
    for (const ShotSize& z : model->shot_sizes) sum += z.count_fraction;
    EXPECT_NEAR(sum, 1.0, 1e-15);
    EXPECT_DOUBLE_EQ(model->max_shot_radius_m, 0.355e-3);
    EXPECT_DOUBLE_EQ(model->min_shot_radius_m, 0.2125e-3);
    EXPECT_DOUBLE_EQ(model->shot_sizes[1].mass_kg, sphere_mass_kg(0.6e-3, 7800.0));
    // Sieve data are rounded: fractions summing to 0.998 are scaled to 1.
    const SceneDescription rounded =
        parse_scene_file(kMixScene, {"shot.sizes=[{diameter: 0.6 mm, fraction: 0.499}, {diameter: 0.5 mm, fraction: 0.499}]"});
    EXPECT_DOUBLE_EQ(rounded.shot.sizes[0].fraction, 0.5);
    // The resolved scene reads back to the same mix.
    TempDir dir;
    std::ofstream((dir.path / "resolved.yaml").string()) << resolved_scene_yaml(s);
    const SceneDescription again = parse_scene_file((dir.path / "resolved.yaml").string());
    ASSERT_EQ(again.shot.sizes.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) {
        EXPECT_EQ(again.shot.sizes[k].diameter_m, s.shot.sizes[k].diameter_m);
        EXPECT_EQ(again.shot.sizes[k].fraction, s.shot.sizes[k].fraction);
    }
    EXPECT_EQ(scene_hash(again), scene_hash(s));
}

// What a mix may not be: each refusal names the field and what was expected.
TEST(ShotMix, BadMixesAreRefusedWithTheFieldAndTheExpectation) {
    const struct {
        std::vector<std::string> set;
        std::string field, expected;
    } cases[] = {
        {{"shot.diameter=0.6 mm"}, "shot.sizes", "give either shot.diameter (one size) or shot.sizes (a mix), not both"},
        {{"shot.sizes=[{diameter: 0.6 mm, fraction: 0.5}, {diameter: 0.5 mm, fraction: 0.4}]"},
         "shot.sizes",
         "expected the fractions to sum to 1 (within 0.005), got 0.9"},
        {{"shot.sizes=[{diameter: 0.6 mm, fraction: 0.5}, {diameter: 0.6 mm, fraction: 0.5}]"},
         "shot.sizes[1].diameter",
         "this diameter is already in the mix"},
        {{"shot.sizes=[]"}, "shot.sizes", "expected at least one size"},
        {{"shot.sizes=[{diameter: 0.6 mm}]"}, "shot.sizes[0].fraction", "missing required key"},
        {{"shot.sizes=[{diameter: 0 mm, fraction: 1}]"}, "shot.sizes[0].diameter", ""},
        {{"shot.fractions_by=volume"}, "shot.fractions_by", "mass"},
        {{"accuracy.scheme=soft"}, "shot.sizes", "the soft scheme's Hertz-Mindlin pairs are built for one shot size"},
    };
    for (const auto& c : cases) {
        try {
            (void)compile_model(parse_scene_file(kMixScene, c.set));
            ADD_FAILURE() << c.set[0] << ": accepted";
        } catch (const InputError& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(c.field), std::string::npos) << c.set[0] << ": " << msg;
            EXPECT_NE(msg.find(c.expected), std::string::npos) << c.set[0] << ": " << msg;
            // Where the bad value came from: the --set, or the file's line it clashes with.
            EXPECT_TRUE(msg.find("--set") != std::string::npos || msg.find("nozzle-mix.yaml:") != std::string::npos) << msg;
        }
    }
    // fractions_by belongs to a mix.
    try {
        (void)parse_scene_file(kStudyScene, {"shot.fractions_by=count"});
        ADD_FAILURE() << "fractions_by with one diameter accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("'fractions_by' is only for a mix"), std::string::npos) << e.what();
    }
}

// Drag depends on the size: each size flies its own flight model. With a constant C_d 0.44, a shot
// of radius R at v in still air decelerates by 3 rho_air C_d |v| v / (8 rho R) besides gravity.
TEST(ShotMix, EachSizeFliesItsOwnDrag) {
    const auto model = compile_model(parse_scene_file(kMixScene, {"air.drag=sphere", "air.drag_coefficient=0.44"}));
    EXPECT_EQ(model->scheme, SteppingScheme::step);
    const Vec3 v(0.0, 0.0, -100.0);
    double bound = 0.0;
    for (const ShotSize& z : model->shot_sizes) {
        const Vec3 a = z.flight->acceleration(Vec3::Zero(), v);
        const double drag = 3.0 * 1.205 * 0.44 * 100.0 * 100.0 / (8.0 * 7800.0 * z.radius_m);
        EXPECT_NEAR(a.z(), -9.81 + drag, 1e-12 * drag) << "R " << z.radius_m;
        bound = std::max(bound, z.flight->speed_gain_bound());
    }
    // The smallest shot slows most; the step sizes by the largest speed gain of any size.
    EXPECT_GT(model->shot_sizes[3].flight->acceleration(Vec3::Zero(), v).z(),
              model->shot_sizes[0].flight->acceleration(Vec3::Zero(), v).z());
    EXPECT_EQ(model->flight_speed_gain_bound_m_per_s2, bound);
}

TEST(ShotMix, EmissionsDrawTheirSizesAtTheSharesAndARedrawKeepsItsSize) {
    // 1 s of the nozzle (135,000 shot/s): room for the 40,000 emissions looked at.
    const auto model = compile_model(parse_scene_file(kMixScene, {"process.duration=1 s"}));
    const ShotSource& source = *model->sources[0];
    const int n = 40000;
    ASSERT_TRUE(source.emission(n));
    std::vector<int> count(model->shot_sizes.size(), 0);
    for (int k = 0; k < n; ++k) {
        const Emission e = *source.emission(static_cast<std::uint64_t>(k));
        ++count[static_cast<std::size_t>(e.size)];
        // Another attempt of the same emission moves the shot, never changes its size.
        const Emission again = *source.emission(static_cast<std::uint64_t>(k), 3);
        EXPECT_EQ(again.size, e.size);
        EXPECT_NE(again.position_m, e.position_m);
    }
    for (std::size_t z = 0; z < count.size(); ++z) {
        const double p = model->shot_sizes[z].count_fraction;
        // Binomial: 5 standard deviations.
        EXPECT_NEAR(count[z], n * p, 5.0 * std::sqrt(n * p * (1.0 - p))) << "size " << z;
    }
    // A scene of one size draws nothing: the same nozzle emits the same shot, all of size 0.
    const auto one = compile_model(parse_scene_file(kMixScene, {"process.duration=1 s", "shot.sizes=[{diameter: 0.6 mm, fraction: 1}]"}));
    EXPECT_FALSE(one->has_size_mix());
    for (int k = 0; k < 100; ++k) {
        const Emission a = *source.emission(static_cast<std::uint64_t>(k)), b = *one->sources[0]->emission(static_cast<std::uint64_t>(k));
        EXPECT_EQ(b.size, 0);
        EXPECT_EQ(a.position_m, b.position_m);
        EXPECT_EQ(a.velocity_m_per_s, b.velocity_m_per_s);
    }
}

// A USP chamber loaded with a mix: 200 shot of 1, 2 and 3 mm by count thrown up from the plate.
TestSceneSpec usp_mix(const std::string& scheme) {
    TestSceneSpec spec = thrown_shot_scene(200, 0.3);
    spec.shot_sizes = {{1e-3, 0.5}, {2e-3, 0.3}, {3e-3, 0.2}};
    spec.chamber_size_m = Vec3(30e-3, 30e-3, 25e-3);
    spec.scheme = scheme;
    return spec;
}

TEST(ShotMix, PlacedShotDrawTheirSizesApartFromThePlacement) {
    const TestScene scene(usp_mix("event"));
    const auto model = scene.compile();
    const InitialShots shots = place_shots(*model);
    ASSERT_EQ(shots.sizes.size(), 200u);
    std::vector<int> count(3, 0);
    for (int z : shots.sizes) ++count[static_cast<std::size_t>(z)];
    EXPECT_NEAR(count[0], 100, 5.0 * std::sqrt(200 * 0.25));
    EXPECT_GT(count[2], 10);
    // Placed apart by the largest size: no two overlap whatever they drew.
    for (std::size_t i = 0; i < shots.positions.size(); ++i)
        for (std::size_t j = i + 1; j < shots.positions.size(); ++j) EXPECT_GE((shots.positions[i] - shots.positions[j]).norm(), 3e-3);
    // The same seed, the same sizes.
    EXPECT_EQ(place_shots(*model).sizes, shots.sizes);
}

class ShotMixRun : public ::testing::TestWithParam<std::string> {};

// Pauses at n evenly spaced times up to the scene's end, t_k = duration k / n (s), and calls `at`
// with the state at the first step end at or past each (the event-driven schemes stop exactly
// there); `each` sees every step's impacts first.
LoopHooks at_even_times(const Model& model, int n, std::function<void(const Simulation&)> at,
                        std::function<void(const std::vector<ImpactRecord>&)> each = {}) {
    const auto next = std::make_shared<int>(1);  // k of the next time, shared by the two hooks
    const auto time_s = [duration_s = model.duration_s, n](int k) { return duration_s * k / n; };
    LoopHooks hooks;
    hooks.after_step = [=](const Simulation& sim, const std::vector<ImpactRecord>& impacts) {
        if (each) each(impacts);
        for (; *next <= n && sim.state().time.seconds() >= time_s(*next); ++*next) at(sim);
    };
    hooks.pause_at_s = [=](const Simulation&) { return *next <= n ? time_s(*next) : std::numeric_limits<double>::infinity(); };
    return hooks;
}

// Two shot of different sizes meet head on in free space (no gravity): a 2 mm shot at +1 m/s and
// a 1 mm one (an eighth of its mass) at -1 m/s, centres 10 mm apart. They touch when the centres
// are R_i + R_j = 1.5 mm apart, at t = 8.5 mm / 2 m/s = 4.25 ms; the exchange (1 + C) dV (C =
// 0.9 (2 / 0.5)^-1/4, the pair's plastic regime) is shared 1/9 : 8/9.
TEST_P(ShotMixRun, TwoSizesCollideAtTheSumOfTheirRadiiWithMomentumKept) {
    TestSceneSpec spec;
    spec.shot_count = 2;
    spec.shot_sizes = {{2e-3, 0.5}, {1e-3, 0.5}};
    spec.gravity_m_per_s2 = Vec3::Zero();
    spec.scheme = GetParam();
    spec.duration_s = 6e-3;  // s, looked at 1.75 ms after the touch
    const TestScene scene(spec);
    Simulation sim(scene.compile());
    const double z = 10e-3;
    sim.edit_state([&](SimulationState& s) {
        s.shots.size_class[0] = 0;
        s.shots.size_class[1] = 1;
        set_shot(s, 0, Vec3(-5e-3, 0, z), Vec3(1, 0, 0));
        set_shot(s, 1, Vec3(5e-3, 0, z), Vec3(-1, 0, 0));
    });
    run_through_loop(sim);
    const SimulationState& s = sim.state();
    EXPECT_EQ(s.shot_shot_impacts, 1u);
    const double C = contact::normal_restitution(2.0, 0.9, 0.5), exchange = (1.0 + C) * 2.0;
    const double v0 = 1.0 - exchange / 9.0, v1 = -1.0 + 8.0 * exchange / 9.0;
    const double t_touch = 4.25e-3, after = s.time.seconds() - t_touch;
    EXPECT_NEAR(s.shots.vx[0], v0, 1e-12);
    EXPECT_NEAR(s.shots.vx[1], v1, 1e-12);
    EXPECT_NEAR(8.0 * s.shots.vx[0] + s.shots.vx[1], 8.0 - 1.0, 1e-12);  // momentum in units of the small shot's mass
    // Where they are now says when they touched: exact in the event scheme; time stepping finds the
    // touch within its step by the exact relative motion too.
    EXPECT_NEAR(s.shots.x[0], -5e-3 + t_touch + v0 * after, 1e-12);
    EXPECT_NEAR(s.shots.x[1], 5e-3 - t_touch + v1 * after, 1e-12);
    EXPECT_EQ(s.health.serious(), 0u);
}

TEST_P(ShotMixRun, AMixInAUspChamberStaysApartAndHealthy) {
    const TestScene scene(usp_mix(GetParam()));
    const auto model = scene.compile();
    Simulation sim(model);
    OverlapAudit audit(*model, 1e-9);
    run_through_loop(sim, at_even_times(*model, 30, [&](const Simulation&) { audit.audit(sim.state()); }));  // audited every 10 ms
    const SimulationState& s = sim.state();
    EXPECT_EQ(s.health.serious(), 0u) << audit.summary();
    EXPECT_EQ(s.shots_per_size, (std::vector<std::uint64_t>{
                                    static_cast<std::uint64_t>(std::count(s.shots.size_class.begin(), s.shots.size_class.end(), 0)),
                                    static_cast<std::uint64_t>(std::count(s.shots.size_class.begin(), s.shots.size_class.end(), 1)),
                                    static_cast<std::uint64_t>(std::count(s.shots.size_class.begin(), s.shots.size_class.end(), 2))}));
    // Each shot against its own radius: the event scheme keeps every pair and surface apart; time
    // stepping's overlaps stay within a step's relative travel (a quarter of the smallest radius).
    const OverlapReport& r = audit.report();
    std::cout << "[ mix      ] " << GetParam() << ": " << audit.summary() << "\n";
    if (GetParam() == "event") {
        EXPECT_EQ(r.pair_overlaps, 0u) << r.worst_pair;
        EXPECT_EQ(r.mesh_overlaps, 0u) << r.worst_mesh;
    } else {
        EXPECT_GT(r.worst_pair_gap_m, -0.25 * 0.5e-3) << r.worst_pair;
        EXPECT_GT(r.worst_mesh_gap_m, -0.25 * 0.5e-3) << r.worst_mesh;
    }
    // All three sizes are in the run.
    for (int z = 0; z < 3; ++z) EXPECT_GT(std::count(s.shots.size_class.begin(), s.shots.size_class.end(), z), 10) << "size " << z;
}

TEST_P(ShotMixRun, TheJetLogsEverySizeWithItsDiameterAndKeepsShotApart) {
    const auto model = compile_model(parse_scene_file(kMixScene, {"accuracy.scheme=" + GetParam(), "process.duration=10 ms"}));
    Simulation sim(model);
    OverlapAudit audit(*model, 1e-9 * 0.71e-3);
    std::map<double, int> logged;
    run_through_loop(sim, at_even_times(  // audited every 0.5 ms
                              *model, 20, [&](const Simulation&) { audit.audit(sim.state()); },
                              [&](const std::vector<ImpactRecord>& impacts) {
                                  for (const ImpactRecord& r : impacts) ++logged[r.shot_diameter_m];
                              }));
    const SimulationState& s = sim.state();
    EXPECT_EQ(s.health.serious(), 0u);
    ASSERT_EQ(logged.size(), 4u);  // every size, with its own diameter
    for (const ShotSize& z : model->shot_sizes) EXPECT_GT(logged[2.0 * z.radius_m], 20) << 2.0 * z.radius_m;
    // Placed + emitted = collected + lost + in the run, by size too.
    std::uint64_t emitted = 0;
    for (std::uint64_t n : s.shots_per_size) emitted += n;
    EXPECT_EQ(emitted, s.emitted_per_source[0]);
    if (GetParam() == "event") {
        EXPECT_EQ(audit.report().pair_overlaps, 0u) << audit.report().worst_pair;
    }
}

TEST_P(ShotMixRun, AResumedMixRunIsTheUninterruptedOne) {
    TempDir dir;
    // Past the event-driven scheme's first restart point (0.1 s), where the stopped run checkpoints;
    // time stepping checkpoints where it stops, so 30 ms of it do (150 ms took 9 s).
    const std::vector<std::string> set{"accuracy.scheme=" + GetParam(),
                                       GetParam() == "event" ? "process.duration=150 ms" : "process.duration=30 ms"};
    const std::string whole = (dir.path / "whole").string(), parts = (dir.path / "parts").string();
    ASSERT_EQ(run_in_process({kMixScene, whole, false, false, {}, set}).code, kExitOk);
    const InProcessResult stopped = run_in_process({kMixScene, parts, false, false, 7, set});
    ASSERT_EQ(stopped.code, kExitInterrupted) << stopped.err;
    const InProcessResult resumed = run_in_process({kMixScene, parts, true, false, {}, set});
    ASSERT_EQ(resumed.code, kExitOk) << resumed.err;
    const std::string log = read_file(whole + "/impacts.csv");
    EXPECT_EQ(log.substr(0, log.find('\n')), impact_csv_header(true));
    EXPECT_EQ(read_file(parts + "/impacts.csv"), log);
    EXPECT_NE(read_file(parts + "/summary.json").find("\"shot_sizes\""), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Schemes, ShotMixRun, ::testing::Values("step", "event"));

// `peensim analyze` of a mix: each impact's energy is its own shot's (the triangles' energies sum to
// the log's sum of 1/2 rho pi D^3 / 6 v_n^2 with each row's D), and the report's "Shot sizes" table
// counts each size's impacts as the log does.
TEST(ShotMix, TheAnalysisWeighsEachImpactByItsOwnShot) {
    TempDir dir;
    const std::string out = (dir.path / "run").string();
    ASSERT_EQ(run_in_process({kMixScene, out, false, true, {}, {"process.duration=10 ms"}}).code, kExitOk);
    std::istringstream log(read_file(out + "/impacts.csv"));
    std::string line;
    std::getline(log, line);
    ASSERT_EQ(line, impact_csv_header(true));
    std::map<double, int> count;  // diameter (m) -> impacts
    double energy = 0.0;
    while (std::getline(log, line)) {
        std::vector<std::string> f;
        std::istringstream fields(line);
        for (std::string x; std::getline(fields, x, ',');) f.push_back(x);
        ASSERT_EQ(f.size(), 17u);
        const double vn = std::stod(f[10]), D = std::stod(f[16]);
        energy += 0.5 * sphere_mass_kg(D, 7800.0) * vn * vn;
        ++count[D];
    }
    std::istringstream triangles(read_file(out + "/analysis/target_triangles.csv"));
    std::getline(triangles, line);
    ASSERT_TRUE(line.starts_with("triangle,facet,area_mm2,impacts,impacts_per_mm2_s,mean_vn_mps,max_vn_mps,energy_J_per_m2,coverage,"))
        << line;
    double summed = 0.0;
    while (std::getline(triangles, line)) {
        std::vector<std::string> f;
        std::istringstream fields(line);
        for (std::string x; std::getline(fields, x, ',');) f.push_back(x);
        summed += std::stod(f[7]) * std::stod(f[2]) * 1e-6;  // J/m2 times m2
    }
    EXPECT_NEAR(summed, energy, 1e-6 * energy);  // the CSV's 7 significant digits (one mean mass would be ~30 % off)
    const std::string report = read_file(out + "/analysis/report.md");
    ASSERT_NE(report.find("## Shot sizes"), std::string::npos);
    ASSERT_EQ(count.size(), 4u);
    const std::pair<double, const char*> labels[] = {{0.71e-3, "0.71"}, {0.6e-3, "0.6"}, {0.5e-3, "0.5"}, {0.425e-3, "0.425"}};
    for (const auto& [D, label] : labels) {
        const auto n = std::find_if(count.begin(), count.end(), [&](const auto& c) { return std::abs(c.first - D) < 1e-12; });
        ASSERT_NE(n, count.end()) << label;
        EXPECT_NE(report.find("| target | " + std::string(label) + " | " + std::to_string(n->second) + " |"), std::string::npos)
            << label << " mm: " << n->second << " impacts\n"
            << report;
    }
}

}  // namespace
}  // namespace peensim::testing
