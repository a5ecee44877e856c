// Pluggable contact laws: the contact policy's rules, the law catalogue, the impact-history law
// (exact restitution by hit count, its marks against a brute-force search), the facet index, laws
// selected by the scene (and refused with file, line and field), a law's per-triangle state kept
// in the simulation state and the checkpoint, and a law written here plugged into a model without
// touching either scheme.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <set>
#include <stdexcept>
#include <string>

#include "app/checkpoint/checkpoint.h"
#include "app/run/run_job.h"
#include "common/input_error.h"
#include "contact/contact_policy.h"
#include "contact/dent.h"
#include "contact/facet_index.h"
#include "contact/impact_history_law.h"
#include "contact/impulse_laws.h"
#include "contact/law_registry.h"
#include "engine/law_input.h"
#include "engine/simulation.h"
#include "kernels/closest_point.h"
#include "model/model.h"
#include "output/impact_csv_writer.h"
#include "scene/scene_parser.h"
#include "support/files.h"
#include "support/run_in_process.h"
#include "support/run_through_loop.h"
#include "support/temp_dir.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;
using contact::ShotShotMode;

// A flat square of n x n cells, two triangles each, in z = 0 (m).
std::vector<Vec3> flat_grid(int n, double cell_m) {
    std::vector<Vec3> corners;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Vec3 a(i * cell_m, j * cell_m, 0), b((i + 1) * cell_m, j * cell_m, 0), c((i + 1) * cell_m, (j + 1) * cell_m, 0),
                d(i * cell_m, (j + 1) * cell_m, 0);
            for (const Vec3& p : {a, b, c, a, c, d}) corners.push_back(p);
        }
    return corners;
}

std::set<std::size_t> brute_force_within(const std::vector<Vec3>& corners, const Vec3& p, double radius_m) {
    std::set<std::size_t> out;
    for (std::size_t t = 0; t < corners.size() / 3; ++t)
        if ((closest_point_on_triangle(p, corners[3 * t], corners[3 * t + 1], corners[3 * t + 2]).point - p).norm() <= radius_m)
            out.insert(t);
    return out;
}

TEST(ContactPolicy, RidesOnlyWhenThePlatePressesAndTheReboundIsBelowTheRideSpeed) {
    EXPECT_TRUE(contact::rebound_rides(1e5, 0.0));
    EXPECT_TRUE(contact::rebound_rides(1e5, 0.999e-3));
    EXPECT_FALSE(contact::rebound_rides(1e5, 1e-3));
    EXPECT_FALSE(contact::rebound_rides(0.0, 0.0));  // the plate does not press: no ride
    EXPECT_FALSE(contact::rebound_rides(-1.0, 0.0));
    EXPECT_TRUE(contact::rebound_rides(1e5, 1.5e-3, 2e-3));  // a scheme whose resolution is coarser
}

TEST(ContactPolicy, ShotShotModeFollowsTheSchemesResolutionAndTheTcWindow) {
    EXPECT_EQ(contact::shot_shot_mode(0.01, 0.05, false), ShotShotMode::sustained);
    EXPECT_EQ(contact::shot_shot_mode(0.05, 0.05, true), ShotShotMode::sustained);  // not faster than the resolution
    EXPECT_EQ(contact::shot_shot_mode(0.06, 0.05, false), ShotShotMode::law);
    EXPECT_EQ(contact::shot_shot_mode(0.06, 0.05, true), ShotShotMode::collapse_guard);
}

TEST(ContactShotShotModes, SustainedStopsTheApproachAndTheCollapseGuardLosesNothingBelowV0) {
    const contact::ImpulseShotShotLaw law({0.5, 1.0, 0.0, 0.0});
    contact::ShotShotInput in{Vec3(0.25, 0, 0), Vec3(-0.25, 0, 0), Vec3(1, 0, 0)};  // approach 0.5 m/s (< V0)
    in.mode = ShotShotMode::sustained;
    const contact::ShotShotResponse s = law.respond(in);
    EXPECT_EQ(s.v_i, Vec3::Zero());
    EXPECT_EQ(s.v_j, Vec3::Zero());
    in.mode = ShotShotMode::collapse_guard;
    const contact::ShotShotResponse g = law.respond(in);
    EXPECT_EQ(g.v_i, Vec3(-0.25, 0, 0));  // elastic exchange below V0
    EXPECT_EQ(g.v_j, Vec3(0.25, 0, 0));
    // Above V0 the guard keeps the plastic regime's loss: approach 16 m/s = 16 V0 -> C = 1/2.
    const contact::ShotShotResponse p = law.respond({Vec3(8, 0, 0), Vec3(-8, 0, 0), Vec3(1, 0, 0), ShotShotMode::collapse_guard});
    EXPECT_EQ(p.v_i, Vec3(-4, 0, 0));
    EXPECT_EQ(p.v_j, Vec3(4, 0, 0));
    in.mode = ShotShotMode::law;
    const contact::ShotShotResponse l = law.respond(in);
    EXPECT_EQ(l.v_i, Vec3(-0.125, 0, 0));  // C0 = 0.5
}

TEST(ContactShotShotModes, AHeldPartnerTakesNothingAndTheShotTakesTheWholeImpulse) {
    // A shot in a pile's substep against a neighbour held like a wall: sustained stops its approach
    // entirely (not half of it), the neighbour's velocity is untouched.
    const contact::ImpulseShotShotLaw law({0.5, 1.0, 0.0, 0.0});
    contact::ShotShotInput in{Vec3(0.75, 0.125, 0), Vec3(-0.25, 0, 0), Vec3(1, 0, 0), ShotShotMode::sustained};  // approach 1 m/s
    in.j_held = true;
    const contact::ShotShotResponse s = law.respond(in);
    EXPECT_EQ(s.v_i, Vec3(-0.25, 0.125, 0));  // moves with the held one along n
    EXPECT_EQ(s.v_j, Vec3(-0.25, 0, 0));
    // With the law's restitution (C0 = 0.5 below V0): it rebounds at half the approach.
    in.mode = ShotShotMode::law;
    EXPECT_EQ(law.respond(in).v_i, Vec3(-0.75, 0.125, 0));
}

TEST(ContactLawCatalogue, EveryLawIsRegisteredOnceWithItsParameters) {
    EXPECT_EQ(contact::law_names_text(), "impulse, impact-history, hertz-mindlin, linear-spring-dashpot");
    EXPECT_EQ(contact::soft_law_names_text(), "'hertz-mindlin', 'linear-spring-dashpot'");
    const contact::LawEntry* impulse = contact::find_law("impulse");
    ASSERT_NE(impulse, nullptr);
    ASSERT_EQ(impulse->shot_shot_parameters.size(), 2u);
    EXPECT_EQ(impulse->shot_shot_parameters[0].name, "C0");
    EXPECT_EQ(impulse->shot_shot_parameters[1].name, "V0");
    EXPECT_EQ(impulse->surface_parameters.size(), 4u);
    ASSERT_NE(impulse->make_shot_shot, nullptr);
    const contact::LawEntry* history = contact::find_law("impact-history");
    ASSERT_NE(history, nullptr);
    EXPECT_EQ(history->make_shot_shot, nullptr);  // a surface law: the surface remembers, not the shot
    EXPECT_TRUE(history->surface_parameters[0].list);
    EXPECT_EQ(contact::find_law("hertz"), nullptr);
    // The impact-history law needs the material's yield stress (eq. 10 sizes its marks).
    contact::SurfacePair pair;
    pair.material = "aluminium";
    pair.triangle_corners_m = [] { return flat_grid(2, 1e-3); };
    const contact::ParameterValues values{
        {{"restitution_by_hits", {0.4, 0.57}}, {"mu", {0.8}}, {"f", {0.1}}, {"influence_distance", {0.0}}}};
    try {
        (void)history->make_surface(values, pair);
        FAIL() << "no yield stress must be refused";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("materials.aluminium.yield_stress"), std::string::npos) << e.what();
    }
    pair.yield_stress_pa = 300e6;
    pair.shot_diameter_m = 1e-3;
    pair.shot_density_kg_per_m3 = 7800;
    const auto law = history->make_surface(values, pair);
    EXPECT_EQ(law->name(), "impact-history");
    EXPECT_EQ(law->state_per_triangle(), 1);
}

TEST(FacetIndex, VisitsExactlyTheTrianglesWithinTheRadiusOnce) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-5e-3, 5e-3), size(1e-5, 2e-3);
    std::vector<Vec3> corners;
    for (int t = 0; t < 400; ++t) {
        const Vec3 c(u(rng), u(rng), u(rng));
        const double s = size(rng);
        for (int k = 0; k < 3; ++k) corners.push_back(c + s * Vec3(u(rng), u(rng), u(rng)) / 5e-3);
    }
    const contact::FacetIndex index(corners, 1e-3);
    for (int q = 0; q < 200; ++q) {
        const Vec3 p(u(rng), u(rng), u(rng));
        const double r = q < 190 ? 0.5 * size(rng) : 0.05;  // some queries wider than the mesh
        std::multiset<std::size_t> seen;
        index.for_each_within(p, r, [&](std::size_t t) { seen.insert(t); });
        const std::set<std::size_t> expected = brute_force_within(corners, p, r);
        EXPECT_EQ(std::set<std::size_t>(seen.begin(), seen.end()), expected) << "query " << q;
        EXPECT_EQ(seen.size(), expected.size()) << "a triangle visited twice, query " << q;
    }
}

TEST(ImpactHistoryLaw, RestitutionByHitCountAndMarksWithinOneDentDiameter) {
    // 1 mm steel shot, 345 MPa part: at 5 m/s the dent (eq. 10) is
    // 1 mm (8 7800 25 / (9 345e6))^(1/4) = 0.1497 mm: a 40 x 40 grid of 25 um cells resolves it.
    contact::ImpactHistoryGeometry g{flat_grid(40, 25e-6), 1e-3, 7800, 345e6};
    const contact::ImpactHistoryLaw law({0.4, 0.5, 0.57}, 0.8, 0.1, 0.0, g);
    std::vector<double> marks(g.corners_m.size() / 3, 0.0);
    const Vec3 point(0.5e-3 + 3e-6, 0.5e-3 + 7e-6, 0.0);
    const std::size_t hit = [&] {
        for (std::size_t t = 0; t < marks.size(); ++t)
            if (brute_force_within(g.corners_m, point, 0.0).count(t)) return t;
        return marks.size();
    }();
    ASSERT_LT(hit, marks.size());
    contact::SurfaceContactInput in{Vec3(0.5, 0, -5), Vec3::Zero(), Vec3::UnitZ()};
    in.triangle = static_cast<int>(hit);
    in.point_local = point;
    in.impact = true;
    in.shot_radius_m = 0.5e-3;
    const double dent = dent_diameter(1e-3, 7800, 5.0, 345e6);
    EXPECT_NEAR(dent, 0.1497e-3, 0.0001e-3);
    const std::set<std::size_t> patch = brute_force_within(g.corners_m, point, dent);
    ASSERT_GT(patch.size(), 20u);
    // Fresh: C = 0.4 (exact: 0.4 * 5 = 2), tangential 0.8 * 0.5.
    contact::SurfaceContactResponse r = law.impact(in, marks);
    EXPECT_EQ(r.v_shot, Vec3(0.4, 0, 2.0));
    for (std::size_t t = 0; t < marks.size(); ++t) EXPECT_EQ(marks[t], patch.count(t) ? 1.0 : 0.0) << "triangle " << t;
    // Hit once before: 0.5; twice: 0.57; the table's last value from then on.
    EXPECT_EQ(law.impact(in, marks).vn_out, 2.5);
    EXPECT_DOUBLE_EQ(law.impact(in, marks).vn_out, 0.57 * 5.0);
    EXPECT_DOUBLE_EQ(law.impact(in, marks).vn_out, 0.57 * 5.0);
    EXPECT_EQ(marks[hit], 4.0);
    // A slower contact (not an impact) rebounds by the table and marks nothing.
    in.impact = false;
    const std::vector<double> before = marks;
    EXPECT_DOUBLE_EQ(law.impact(in, marks).vn_out, 0.57 * 5.0);
    EXPECT_EQ(marks, before);
    // A spot far from the marks is fresh.
    const Vec3 far(0.05e-3, 0.95e-3, 0.0);
    for (std::size_t t : brute_force_within(g.corners_m, far, 0.0)) {
        in.triangle = static_cast<int>(t);
        in.point_local = far;
        EXPECT_EQ(law.impact(in, marks).vn_out, 2.0);
    }
    // What the run's summary prints of the state.
    EXPECT_EQ(law.describe_state(marks),
              std::to_string(patch.size()) + " of 3200 triangles hit, up to 4 times (next restitution there 0.4-0.57)");
    // Sustained contact is the impulse law's Coulomb friction (f = 0.1, 9.81 m/s2, 0.01 s).
    const contact::SurfaceContactResponse s = law.sustain({Vec3(0.3, 0, 0), Vec3::Zero(), Vec3::UnitZ(), 9.81, 0.01}, marks);
    EXPECT_NEAR(s.v_shot.x(), 0.3 - 0.1 * 9.81 * 0.01, 1e-15);
}

TEST(ImpactHistoryLaw, EachImpactMarksItsOwnShotsDent) {
    // A mix: the law is built once (sized by the largest shot), and each impact's dent (eq. 10)
    // scales with its own shot's diameter. A 0.5 mm shot at 5 m/s dents 0.0749 mm, a 1 mm shot twice that.
    contact::ImpactHistoryGeometry g{flat_grid(40, 25e-6), 1e-3, 7800, 345e6};
    const contact::ImpactHistoryLaw law({0.4, 0.5}, 0.8, 0.1, 0.0, g);
    const Vec3 point(0.5e-3 + 3e-6, 0.5e-3 + 7e-6, 0.0);
    contact::SurfaceContactInput in{Vec3(0, 0, -5), Vec3::Zero(), Vec3::UnitZ()};
    in.point_local = point;
    in.impact = true;
    for (std::size_t t : brute_force_within(g.corners_m, point, 0.0)) in.triangle = static_cast<int>(t);
    for (const double D : {0.5e-3, 1e-3}) {
        std::vector<double> marks(g.corners_m.size() / 3, 0.0);
        in.shot_radius_m = 0.5 * D;
        law.impact(in, marks);
        const std::set<std::size_t> patch = brute_force_within(g.corners_m, point, dent_diameter(D, 7800, 5.0, 345e6));
        for (std::size_t t = 0; t < marks.size(); ++t) EXPECT_EQ(marks[t], patch.count(t) ? 1.0 : 0.0) << "D " << D << " triangle " << t;
    }
    EXPECT_LT(brute_force_within(g.corners_m, point, dent_diameter(0.5e-3, 7800, 5.0, 345e6)).size(),
              brute_force_within(g.corners_m, point, dent_diameter(1e-3, 7800, 5.0, 345e6)).size() / 2);
}

TEST(ImpactHistoryLaw, AFixedInfluenceDistanceMarksAsFarWhateverTheDent) {
    // The DEM-FEM study's region of influence: one shot diameter (0.58 mm) around every impact,
    // whatever its speed or the part's yield stress (none needed then).
    contact::ImpactHistoryGeometry g{flat_grid(40, 50e-6), 0.58e-3, 7800, 0.0};
    const contact::ImpactHistoryLaw law({0.4, 0.6}, 0.71, 0.3, 0.58e-3, g);
    const Vec3 point(1e-3 + 3e-6, 1e-3 + 7e-6, 0.0);
    contact::SurfaceContactInput in{Vec3(0, 0, -50), Vec3::Zero(), Vec3::UnitZ()};
    in.point_local = point;
    in.impact = true;
    in.shot_radius_m = 0.29e-3;
    for (std::size_t t : brute_force_within(g.corners_m, point, 0.0)) in.triangle = static_cast<int>(t);
    const std::set<std::size_t> patch = brute_force_within(g.corners_m, point, 0.58e-3);
    for (const double speed : {50.0, 2.0}) {
        std::vector<double> marks(g.corners_m.size() / 3, 0.0);
        in.v_shot = Vec3(0, 0, -speed);
        EXPECT_DOUBLE_EQ(law.impact(in, marks).vn_out, 0.4 * speed);
        for (std::size_t t = 0; t < marks.size(); ++t)
            EXPECT_EQ(marks[t], patch.count(t) ? 1.0 : 0.0) << "speed " << speed << " triangle " << t;
        EXPECT_DOUBLE_EQ(law.impact(in, marks).vn_out, 0.6 * speed);
    }
    // Built from a scene's values without the material's yield stress.
    contact::SurfacePair pair;
    pair.material = "steel";
    pair.triangle_corners_m = [] { return flat_grid(2, 1e-3); };
    pair.shot_diameter_m = 0.58e-3;
    pair.shot_density_kg_per_m3 = 7800;
    const contact::ParameterValues values{
        {{"restitution_by_hits", {0.4, 0.6}}, {"mu", {0.71}}, {"f", {0.3}}, {"influence_distance", {0.58e-3}}}};
    EXPECT_EQ(contact::find_law("impact-history")->make_surface(values, pair)->state_per_triangle(), 1);
}

const std::string kGear = std::string(PEENSIM_SOURCE_DIR) + "/scenes/gear.yaml";
const std::string kHistoryPair =
    "contacts.shot-aluminium-2000={law: impact-history, restitution_by_hits: [0.6, 0.75, 0.85], mu: 0.8, f: 0.1}";

TEST(SceneContactLaws, APairSelectsItsLawAndTheModelBuildsIt) {
    const SceneDescription scene = parse_scene_file(kGear, {kHistoryPair, "process.duration=0.1 s"});
    const ContactPairDesc* pair = nullptr;
    for (const ContactPairDesc& c : scene.contacts)
        if (c.key == "shot-aluminium-2000") pair = &c;
    ASSERT_NE(pair, nullptr);
    EXPECT_EQ(pair->law, "impact-history");
    EXPECT_EQ(pair->values("restitution_by_hits"), (std::vector<double>{0.6, 0.75, 0.85}));
    EXPECT_EQ(pair->value("mu"), 0.8);
    const auto model = compile_model(scene);
    const int gear = model->component_index("gear");
    ASSERT_GE(gear, 0);
    const Component& c = model->components[static_cast<std::size_t>(gear)];
    EXPECT_EQ(c.law->name(), "impact-history");
    EXPECT_EQ(model->components[0].law->name(), "impulse");
    // The state: one mark per gear triangle, nothing for the impulse components (they pay nothing).
    const std::vector<std::vector<double>> state = fresh_law_state(*model);
    EXPECT_EQ(state[static_cast<std::size_t>(gear)].size(), c.mesh->triangle_count());
    for (std::size_t k = 0; k < state.size(); ++k)
        if (static_cast<int>(k) != gear) {
            EXPECT_TRUE(state[k].empty());
        }
}

struct BadLawCase {
    std::vector<std::string> overrides;
    std::string field, expected;
};

TEST(SceneContactLaws, BadLawSettingsAreRefusedWithFieldAndExpectation) {
    const BadLawCase cases[] = {
        {{"contacts.shot-steel.law=hertz"}, "contacts.shot-steel.law", "one of impulse, impact-history"},
        {{"contacts.shot-shot={law: impact-history, restitution_by_hits: [0.5]}"},
         "contacts.shot-shot.law",
         "is for shot-<material> pairs, not between shot"},
        {{"contacts.shot-steel.restitution_by_hits=[0.5]"},
         "contacts.shot-steel.restitution_by_hits",
         "not a parameter of law 'impulse'; expected law, C0, V0, mu, f"},
        {{"contacts.shot-aluminium-2000={law: impact-history}"},
         "contacts.shot-aluminium-2000",
         "law 'impact-history' needs 'restitution_by_hits'"},
        {{"contacts.shot-aluminium-2000={law: impact-history, restitution_by_hits: [0.5, 1.2]}"},
         "contacts.shot-aluminium-2000.restitution_by_hits[1]",
         "in (0, 1]"},
        {{"contacts.shot-aluminium-2000={law: impact-history, restitution_by_hits: []}"},
         "contacts.shot-aluminium-2000.restitution_by_hits",
         "a list of one or more"},
        {{"contacts.shot-aluminium-2000={law: impact-history, restitution_by_hits: [0.5], C0: 0.9}"},
         "contacts.shot-aluminium-2000.C0",
         "expected law, restitution_by_hits, mu, f"},
        {{"contacts.shot-aluminium-2000={law: impact-history, restitution_by_hits: abc}"},
         "contacts.shot-aluminium-2000.restitution_by_hits",
         "expected a list of one or more numbers"},
        // A pair naming no law takes the default's: the message says so.
        {{"contacts.default={law: impact-history, restitution_by_hits: [0.5]}"},
         "contacts.shot-TA6V.C0",
         "takes its law from the `default` pair; write `law:` in it"},
        // The law needs the yield stress: found when the model is built.
        {{"contacts.shot-HDPE={law: impact-history, restitution_by_hits: [0.5]}"}, "contacts.shot-HDPE.law", "materials.HDPE.yield_stress"},
    };
    for (const BadLawCase& c : cases) {
        try {
            (void)compile_model(parse_scene_file(kGear, c.overrides));
            ADD_FAILURE() << c.overrides[0] << ": accepted";
        } catch (const InputError& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(c.field), std::string::npos) << c.overrides[0] << ": " << msg;
            EXPECT_NE(msg.find(c.expected), std::string::npos) << c.overrides[0] << ": " << msg;
        }
    }
}

TEST(SceneContactLaws, TheLawsStateIsCheckpointedAndAResumedRunEqualsTheUninterruptedOne) {
    // The impact-history law changes every rebound on a spot hit before: a resumed run that lost its
    // marks would rebound differently and write other bytes.
    for (const char* scheme : {"step", "event"}) {
        const TempDir dir;
        const std::vector<std::string> overrides{kHistoryPair, "process.duration=0.3 s", std::string("accuracy.scheme=") + scheme,
                                                 "output.checkpoint_interval=0.1 s"};
        const std::string whole = (dir.path / "whole").string(), parts = (dir.path / "parts").string();
        ASSERT_EQ(run_in_process({kGear, whole, false, false, {}, overrides}).code, kExitOk);
        // Stop requests after this much work: time stepping stops at once (400 steps), the event
        // scheme at its next restart point (0.1 s).
        const std::uint64_t work = std::string(scheme) == "step" ? 400 : 30;
        ASSERT_EQ(run_in_process({kGear, parts, false, false, work, overrides}).code, kExitInterrupted) << scheme;
        const Checkpoint cp = load_checkpoint((fs::path(parts) / kCheckpointFileName).string());
        double marks = 0.0;
        for (const std::vector<double>& v : cp.state.law_state)
            for (double x : v) marks += x;
        EXPECT_GT(marks, 0.0) << scheme << ": the checkpoint holds the marks made before it";
        ASSERT_EQ(run_in_process({kGear, parts, true, false, {}, overrides}).code, kExitOk) << scheme;
        const std::string expected = read_file(fs::path(whole) / kImpactCsvFileName);
        EXPECT_GT(std::count(expected.begin(), expected.end(), '\n'), 100) << scheme;
        EXPECT_TRUE(expected == read_file(fs::path(parts) / kImpactCsvFileName)) << scheme << ": the resumed run differs";
    }
}

// A law written here, not in contact/: it rebounds like the impulse law and counts, per
// triangle, the impacts it saw, checking the identity the engine hands it.
class CountingLaw final : public contact::SurfaceLaw {
public:
    CountingLaw(contact::PairCoefficients k, int component, int shot_count) : k_(k), component_(component), shot_count_(shot_count) {}
    std::string_view name() const override { return "counting"; }
    int state_per_triangle() const override { return 1; }
    contact::SurfaceContactResponse impact(const contact::SurfaceContactInput& in, std::span<double> counts) const override {
        EXPECT_EQ(in.component, component_);
        EXPECT_TRUE(in.shot >= 0 && in.shot < shot_count_) << in.shot;
        EXPECT_GT(in.shot_radius_m, 0.0);
        EXPECT_GT(in.shot_mass_kg, 0.0);
        EXPECT_GE(in.time_s, 0.0);
        if (in.impact) {
            EXPECT_TRUE(in.triangle >= 0 && static_cast<std::size_t>(in.triangle) < counts.size()) << in.triangle;
            if (in.triangle >= 0 && static_cast<std::size_t>(in.triangle) < counts.size())
                counts[static_cast<std::size_t>(in.triangle)] += 1.0;
        }
        return contact::impulse_surface_impact(in, k_);
    }
    contact::SurfaceContactResponse sustain(const contact::SurfaceContactInput& in, std::span<double>) const override {
        return contact::impulse_surface_sustain(in, k_.f);
    }

private:
    contact::PairCoefficients k_;
    int component_, shot_count_;
};

TEST(SceneContactLaws, ALawFromOutsideContactPlugsInWithoutTouchingTheSchemes) {
    for (const char* scheme : {"step", "event"}) {
        auto model = std::make_shared<Model>(
            *compile_model(parse_scene_file(kGear, {"process.duration=0.2 s", std::string("accuracy.scheme=") + scheme})));
        const auto gear = static_cast<std::size_t>(model->component_index("gear"));
        model->components[gear].law =
            std::make_shared<CountingLaw>(contact::PairCoefficients{0.95, 0.5, 0.8, 0.1}, static_cast<int>(gear), model->shot_count);
        Simulation sim(model);
        run_through_loop(sim);
        double counted = 0.0;
        for (double x : sim.state().law_state[gear]) counted += x;
        EXPECT_GT(sim.state().impacts_per_component[gear], 50u) << scheme;
        EXPECT_EQ(counted, static_cast<double>(sim.state().impacts_per_component[gear])) << scheme;
    }
}

}  // namespace
}  // namespace peensim::testing
