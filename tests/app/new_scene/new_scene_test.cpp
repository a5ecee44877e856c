// `peensim new` (app/new_scene/): a ready scene around a user's part. On the shipped parts and on
// parts it never saw (an OpenSCAD bracket off the origin, the same in inches, the same moved), the
// scene it writes follows its rules (scene_design.h) to the micrometre, passes `check --strict`
// without a warning, and runs with shot landing on the part; it never writes over a file unasked,
// never over the part, and every bad option is an input error naming the option.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/check/check_job.h"
#include "app/exit_codes.h"
#include "app/new_scene/new_scene_job.h"
#include "app/new_scene/scene_design.h"
#include "geometry/box_mesh.h"
#include "geometry/mesh_loader.h"
#include "geometry/stl_writer.h"
#include "scene/scene_parser.h"
#include "support/files.h"
#include "support/run_in_process.h"
#include "support/temp_dir.h"

namespace peensim {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = PEENSIM_SOURCE_DIR;
const fs::path kBracket = kSource / "tests" / "app" / "new_scene" / "bracket.stl";
constexpr double kMicrometre = 1e-6;  // m: the scene's lengths are written to 1 um

struct NewResult {
    int code = -1;
    std::string out, err;
};

NewResult run_new(NewSceneOptions o) {
    std::ostringstream out, err;
    NewResult r;
    r.code = new_scene_job(o, out, err);
    r.out = out.str();
    r.err = err.str();
    return r;
}

NewSceneOptions options(const fs::path& part, const fs::path& scene) {
    NewSceneOptions o;
    o.part_path = part.string();
    o.scene_path = scene.string();
    return o;
}

// The part turning about its y axis at 30 rpm.
NewSceneOptions turning_about_y(const fs::path& part, const fs::path& scene) {
    NewSceneOptions o = options(part, scene);
    o.rotate_about = "y";
    o.rpm = "30";
    return o;
}

const ComponentDesc& component(const SceneDescription& s, const std::string& name) {
    for (const auto& c : s.components)
        if (c.name == name) return c;
    throw std::runtime_error("no component " + name);
}

// The world bounds of a component as the scene places it (no rotation: `new` never rotates).
void world_bounds(const ComponentDesc& c, Vec3& lo, Vec3& hi) {
    const TriangleMesh m = load_mesh(c.mesh_path, c.mesh_unit_m);
    lo = hi = m.vertices.front();
    for (const Vec3& v : m.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    lo += c.translation_m, hi += c.translation_m;
}

// check --strict: exit 0, no warning.
void expect_checks_clean(const fs::path& scene) {
    std::ostringstream out, err;
    EXPECT_EQ(check_job(scene.string(), {}, true, out, err), kExitOk) << err.str();
    EXPECT_EQ(err.str().find("warning"), std::string::npos) << err.str();
}

// A short run: exit 0 and shot on the part.
std::uint64_t impacts_on_part(const fs::path& scene, const fs::path& out_dir, const std::string& part, const std::string& duration) {
    testing::InProcessRun run;
    run.scene_path = scene.string();
    run.output_dir = out_dir.string();
    run.overrides = {"process.duration=" + duration};
    const testing::InProcessResult r = testing::run_in_process(run);
    EXPECT_EQ(r.code, kExitOk) << r.err;
    std::ifstream in(out_dir / "summary.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const auto& c : j.at("impacts_per_component"))
        if (c.at("component") == part) return c.at("impacts").get<std::uint64_t>();
    return 0;
}

TEST(NewScene, TheShippedGearTurningFollowsTheRulesChecksCleanAndRuns) {
    testing::TempDir dir;
    const NewResult r = run_new(turning_about_y(kSource / "assets" / "gear.stl", dir.path / "my-gear.yaml"));
    ASSERT_EQ(r.code, kExitOk) << r.err;
    EXPECT_NE(r.out.find("sonotrode"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(dir.path / "my-gear-assets" / "chamber.stl"));

    const SceneDescription s = parse_scene_file((dir.path / "my-gear.yaml").string());
    // The gear: tip radius m (z + 2) / 2 = 22 mm, 10 mm wide, turning about y: its footprint
    // sqrt(5^2 + 22^2) mm; the sonotrode 5 mm wider (2.5 shot is less), the chamber's lower wall
    // 0.1 mm beyond it, the upper 15 mm beyond the footprint; the swept solid's lowest point 20 mm up.
    const double footprint = std::hypot(5e-3, 22e-3);
    Vec3 lo, hi;
    world_bounds(component(s, "sonotrode"), lo, hi);
    EXPECT_NEAR(hi.x(), footprint + 5e-3, 2 * kMicrometre + footprint * (1 - std::cos(M_PI / 128)));
    EXPECT_NEAR(hi.z(), 0.0, kMicrometre);
    world_bounds(component(s, "chamber"), lo, hi);
    EXPECT_NEAR(hi.x(), footprint + 15e-3, 2 * kMicrometre);
    const ComponentDesc& gear = component(s, "gear");
    ASSERT_TRUE(gear.rotation_motion.has_value());
    const Vec3 axis_point = gear.translation_m;                   // the gear's centre is its frame's origin
    EXPECT_NEAR(axis_point.z() - 22e-3, 20e-3, 2 * kMicrometre);  // the swept tips' lowest point
    EXPECT_NEAR(axis_point.x(), 0.0, kMicrometre);
    EXPECT_NEAR(s.process.duration_s, 6.0, 1e-12);  // 3 whole turns of 2 s: the fewest covering 5 s
    // 15 % of the sonotrode's face in 2 mm shot.
    EXPECT_EQ(s.shot.count, std::lround(0.15 * std::pow((footprint + 5e-3) / 1e-3, 2)));

    expect_checks_clean(dir.path / "my-gear.yaml");
    EXPECT_GT(impacts_on_part(dir.path / "my-gear.yaml", dir.path / "out", "gear", "1 s"), 0u);
}

TEST(NewScene, TheShippedRodStillStandsOffByItsLowestPoint) {
    testing::TempDir dir;
    const NewResult r = run_new(options(kSource / "assets" / "rod.stl", dir.path / "rod.yaml"));
    ASSERT_EQ(r.code, kExitOk) << r.err;
    const SceneDescription s = parse_scene_file((dir.path / "rod.yaml").string());
    Vec3 lo, hi;
    world_bounds(component(s, "rod"), lo, hi);
    EXPECT_NEAR(lo.z(), 20e-3, kMicrometre);  // the rod (radius 5 mm, axis 20 mm up in its file) 20 mm off the sonotrode
    EXPECT_NEAR(0.5 * (lo.x() + hi.x()), 0.0, kMicrometre);
    EXPECT_NEAR(0.5 * (lo.y() + hi.y()), 0.0, kMicrometre);
    EXPECT_FALSE(component(s, "rod").rotation_motion.has_value());
    EXPECT_NEAR(s.process.duration_s, 5.0, 1e-12);
    EXPECT_EQ(component(s, "rod").regions.size(), 6u);  // by facing direction
    expect_checks_clean(dir.path / "rod.yaml");
}

// The design of a scene, read back: what must not depend on the part's unit or where its file put it.
struct Placed {
    Vec3 part_lo, part_hi, chamber_lo, chamber_hi, sonotrode_hi;
    int shot = 0;
};
Placed placed(const fs::path& scene, const std::string& part) {
    const SceneDescription s = parse_scene_file(scene.string());
    Placed p;
    world_bounds(component(s, part), p.part_lo, p.part_hi);
    world_bounds(component(s, "chamber"), p.chamber_lo, p.chamber_hi);
    Vec3 lo;
    world_bounds(component(s, "sonotrode"), lo, p.sonotrode_hi);
    p.shot = s.shot.count;
    return p;
}
void expect_same(const Vec3& a, const Vec3& b, const char* what) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], 2 * kMicrometre) << what << " " << k;
}
void expect_same(const Placed& a, const Placed& b) {
    expect_same(a.part_lo, b.part_lo, "part lo");
    expect_same(a.part_hi, b.part_hi, "part hi");
    expect_same(a.chamber_lo, b.chamber_lo, "chamber lo");
    expect_same(a.chamber_hi, b.chamber_hi, "chamber hi");
    expect_same(a.sonotrode_hi, b.sonotrode_hi, "sonotrode hi");
    EXPECT_EQ(a.shot, b.shot);
}

TEST(NewScene, AnOpenScadPartOffTheOriginInchesOrMovedGivesTheSameScene) {
    testing::TempDir dir;
    // The bracket as OpenSCAD wrote it (mm, its corner at x = 40 mm).
    ASSERT_EQ(run_new(options(kBracket, dir.path / "bracket.yaml")).code, kExitOk);
    const Placed mm = placed(dir.path / "bracket.yaml", "bracket");
    EXPECT_NEAR(0.5 * (mm.part_lo.x() + mm.part_hi.x()), 0.0, kMicrometre);  // centred over the sonotrode
    EXPECT_NEAR(mm.part_lo.z(), 20e-3, kMicrometre);
    expect_checks_clean(dir.path / "bracket.yaml");
    EXPECT_GT(impacts_on_part(dir.path / "bracket.yaml", dir.path / "out", "bracket", "1 s"), 0u);

    // The same in inches.
    const TriangleMesh bracket = load_mesh(kBracket.string(), 1e-3);
    write_ascii_stl(bracket, (dir.path / "bracket-in.stl").string(), 0.0254);
    NewSceneOptions inches = options(dir.path / "bracket-in.stl", dir.path / "inches.yaml");
    inches.unit = "in";
    ASSERT_EQ(run_new(inches).code, kExitOk);
    expect_same(placed(dir.path / "inches.yaml", "bracket-in"), mm);
    // Read in mm by mistake it is 1.2 mm across: refused, with the unit to check.
    const NewResult wrong = run_new(options(dir.path / "bracket-in.stl", dir.path / "wrong.yaml"));
    EXPECT_EQ(wrong.code, kExitInputError);
    EXPECT_NE(wrong.err.find("--unit"), std::string::npos) << wrong.err;
    EXPECT_FALSE(fs::exists(dir.path / "wrong.yaml"));

    // Moved far off: the same scene, the translation taking the move back.
    TriangleMesh moved = bracket;
    for (Vec3& v : moved.vertices) v += Vec3(0.1, 0.05, -0.03);
    write_binary_stl(moved, (dir.path / "moved.stl").string());
    ASSERT_EQ(run_new(options(dir.path / "moved.stl", dir.path / "moved.yaml")).code, kExitOk);
    expect_same(placed(dir.path / "moved.yaml", "moved"), mm);
}

// Every region `new` writes holds some of the part's surface: the L-bracket turning about y leaves
// three of the eight sectors empty (the L's inside), which are left out and said so; the gear fills
// all eight, which stay one `sectors` entry.
TEST(NewScene, EveryRegionItWritesHoldsSomeOfThePartsSurface) {
    testing::TempDir dir;
    const NewResult r = run_new(turning_about_y(kBracket, dir.path / "turning.yaml"));
    ASSERT_EQ(r.code, kExitOk) << r.err;
    EXPECT_NE(r.out.find("regions the two ends and 5 of 8 sectors about the axis; left out, holding none of its surface: sector-0 "
                         "sector-1 sector-2"),
              std::string::npos)
        << r.out;
    const std::string yaml = testing::read_file(dir.path / "turning.yaml");
    EXPECT_NE(yaml.find("# Left out, as none of the part's surface lies in them: sector-0 sector-1 sector-2."), std::string::npos) << yaml;
    const SceneDescription s = parse_scene_file((dir.path / "turning.yaml").string());
    const ComponentDesc& bracket = component(s, "bracket");
    ASSERT_EQ(bracket.regions.size(), 7u);  // two ends, five sectors
    for (std::size_t i = 2; i < 7; ++i) {
        ASSERT_TRUE(bracket.regions[i].sector.has_value()) << bracket.regions[i].name;
        EXPECT_EQ(bracket.regions[i].name, "sector-" + std::to_string(i + 1));
        // Sector k of 8 spans [45 k - 22.5, 45 k + 22.5) deg, as the `sectors` entry makes it.
        EXPECT_NEAR(bracket.regions[i].sector->from_rad, (45.0 * static_cast<double>(i + 1) - 22.5) * M_PI / 180.0, 1e-12);
        EXPECT_NEAR(bracket.regions[i].sector->to_rad, (45.0 * static_cast<double>(i + 1) + 22.5) * M_PI / 180.0, 1e-12);
    }
    expect_checks_clean(dir.path / "turning.yaml");  // no region that selects none of the surface

    const NewResult gr = run_new(turning_about_y(kSource / "assets" / "gear.stl", dir.path / "gear.yaml"));
    ASSERT_EQ(gr.code, kExitOk) << gr.err;
    EXPECT_NE(gr.out.find("regions the two ends and 8 sectors about the axis\n"), std::string::npos) << gr.out;
    const SceneDescription gs = parse_scene_file((dir.path / "gear.yaml").string());
    const ComponentDesc& gear = component(gs, "gear");
    ASSERT_EQ(gear.regions.size(), 3u);
    ASSERT_TRUE(gear.regions[2].sectors.has_value());
    EXPECT_EQ(gear.regions[2].sectors->count, 8);
}

// A part's mesh with a hole runs, but `new` says what a hole does and how to close it.
TEST(NewScene, AnOpenPartMeshIsWarnedOf) {
    testing::TempDir dir;
    TriangleMesh open = load_mesh(kBracket.string(), 1e-3);
    open.triangles.pop_back();
    write_binary_stl(open, (dir.path / "open.stl").string());
    const NewResult r = run_new(options(dir.path / "open.stl", dir.path / "open.yaml"));
    ASSERT_EQ(r.code, kExitOk) << r.err;
    EXPECT_NE(r.out.find("warning: the part's mesh is not closed (3 edges on one triangle only, 0 on three or more)"), std::string::npos)
        << r.out;
    const NewResult closed = run_new(options(kBracket, dir.path / "closed.yaml"));
    EXPECT_EQ(closed.out.find("not closed"), std::string::npos) << closed.out;
}

TEST(NewScene, ItNeverWritesOverAFileUnaskedNorOverThePart) {
    testing::TempDir dir;
    const fs::path scene = dir.path / "b.yaml";
    ASSERT_EQ(run_new(options(kBracket, scene)).code, kExitOk);
    std::ifstream first(scene);
    const std::string before((std::istreambuf_iterator<char>(first)), {});
    NewSceneOptions again = options(kBracket, scene);
    again.material = "titanium";
    const NewResult refused = run_new(again);
    EXPECT_EQ(refused.code, kExitInputError);
    EXPECT_NE(refused.err.find("exists"), std::string::npos) << refused.err;
    std::ifstream second(scene);
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(second)), {}), before);
    again.force = true;
    EXPECT_EQ(run_new(again).code, kExitOk);
    bool titanium = false;
    for (const MaterialDesc& m : parse_scene_file(scene.string()).materials) titanium = titanium || m.name == "part-TA6V";
    EXPECT_TRUE(titanium);

    // A part whose name is the scene's: refused even with --force, the part untouched.
    fs::copy_file(kBracket, dir.path / "part.yaml");
    NewSceneOptions self = options(dir.path / "part.yaml", dir.path / "part.yaml");
    self.force = true;
    const NewResult r = run_new(self);
    EXPECT_EQ(r.code, kExitInputError);
    EXPECT_NE(r.err.find("the part itself"), std::string::npos) << r.err;
    EXPECT_EQ(fs::file_size(dir.path / "part.yaml"), fs::file_size(kBracket));
}

// A STEP part states its unit: `new` writes no mesh_unit, refuses --unit beside it, and the scene
// it writes checks clean (the rod of scenes/rod.yaml as an exact cylinder, written in mm by
// tests/validation/write_step_rod.cpp).
TEST(NewScene, AStepPartIsReadInItsOwnUnit) {
    testing::TempDir dir;
    const fs::path step = kSource / "tests" / "app" / "new_scene" / "rod.step";
    const NewResult r = run_new(options(step, dir.path / "rod.yaml"));
    ASSERT_EQ(r.code, kExitOk) << r.err;
    EXPECT_NE(r.out.find("read in the file's unit, millimetre)"), std::string::npos) << r.out;  // the unit the file declares
    std::ifstream in(dir.path / "rod.yaml");
    const std::string yaml((std::istreambuf_iterator<char>(in)), {});
    EXPECT_EQ(yaml.find("mesh_unit: mm\n    # Centred"), std::string::npos) << "no mesh_unit for the STEP part";
    const SceneDescription s = parse_scene_file((dir.path / "rod.yaml").string());
    Vec3 lo, hi;
    world_bounds(component(s, "rod"), lo, hi);
    EXPECT_NEAR(hi.y() - lo.y(), 30e-3, kMicrometre);  // 30 mm long, in the file's mm
    EXPECT_NEAR(lo.z(), 20e-3, 2 * kMicrometre);
    expect_checks_clean(dir.path / "rod.yaml");

    NewSceneOptions with_unit = options(step, dir.path / "again.yaml");
    with_unit.unit = "mm";
    const NewResult refused = run_new(with_unit);
    EXPECT_EQ(refused.code, kExitInputError);
    EXPECT_NE(refused.err.find("--unit"), std::string::npos) << refused.err;

    // Its size in doubt (under 5 shot of 10 mm): the question is the file's own unit, not --unit,
    // which it may not take.
    NewSceneOptions large_shot = options(step, dir.path / "large-shot.yaml");
    large_shot.shot_diameter = "10 mm";
    const NewResult doubted = run_new(large_shot);
    EXPECT_EQ(doubted.code, kExitInputError);
    EXPECT_NE(doubted.err.find("was the file exported in the unit it names"), std::string::npos) << doubted.err;
    EXPECT_EQ(doubted.err.find("--unit"), std::string::npos) << doubted.err;
}

// The duration is written to the millisecond; it must not fall short of its last whole turn (45
// rpm: 4 turns are 16/3 s, which written as 5.33333333 s left the analysis 3 turns).
TEST(NewScene, TheDurationHoldsItsWholeTurnsWhateverTheSpeed) {
    const PartEnvelope envelope = part_envelope(load_mesh(kBracket.string(), 1e-3), Axis::z);
    for (double rpm : {7.0, 13.0, 30.0, 45.0, 59.0, 300.0, 2999.0}) {
        NewSceneRequest request;
        request.turning_axis = Axis::z;
        request.rpm = rpm;
        const SceneDesign d = design_scene(envelope, request);
        const double turn_s = 60.0 / rpm;
        EXPECT_GE(d.duration_s, 5.0) << rpm;
        EXPECT_EQ(std::floor(d.duration_s / turn_s * (1.0 + 1e-12)), d.turns) << rpm << " rpm: " << d.duration_s << " s";
        EXPECT_LT(d.duration_s - d.turns * turn_s, 1e-3) << rpm;  // at most a millisecond past the last turn
    }
}

// A part whose chamber would be past the size `peensim check` takes for a unit slip is refused,
// not written with a scene its own check warns on (a 1.5 m box made a 2.15 m chamber); a 1 m
// one gets its scene.
TEST(NewScene, APartWhoseChamberWouldBeImplausibleIsRefused) {
    testing::TempDir dir;
    const auto box_of = [&](double side_mm) {
        const fs::path part = dir.path / ("box-" + std::to_string(static_cast<int>(side_mm)) + ".stl");
        write_binary_stl(box(BoxSpec{Vec3(side_mm, side_mm, 100.0) * 1e-3, Vec3::Zero(), Eigen::Vector3i::Ones()}), part.string(), 1e-3);
        return part;
    };
    const NewResult large = run_new(options(box_of(1500.0), dir.path / "large.yaml"));
    EXPECT_EQ(large.code, kExitInputError) << large.out;
    EXPECT_NE(large.err.find("the chamber around it would be 2151.3 mm across, beyond the 2000.0 mm `peensim check` takes for a unit slip"),
              std::string::npos)
        << large.err;
    EXPECT_FALSE(fs::exists(dir.path / "large.yaml"));
    const NewResult metre = run_new(options(box_of(1000.0), dir.path / "metre.yaml"));
    EXPECT_EQ(metre.code, kExitOk) << metre.err;
    EXPECT_NE(metre.out.find("chamber    1444.2 mm across"), std::string::npos) << metre.out;
}

TEST(NewScene, EveryBadOptionIsAnInputErrorNamingIt) {
    testing::TempDir dir;
    const auto refused = [&](const std::string& option, auto&& change) {
        NewSceneOptions o = options(kBracket, dir.path / "x.yaml");
        change(o);
        const NewResult r = run_new(o);
        EXPECT_EQ(r.code, kExitInputError) << option;
        EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir.path / "x.yaml")) << option;
    };
    refused("--unit", [](NewSceneOptions& o) { o.unit = "furlong"; });
    refused("--rotate-about", [](NewSceneOptions& o) { o.rotate_about = "w", o.rpm = "30"; });
    refused("--rpm", [](NewSceneOptions& o) { o.rotate_about = "y"; });
    refused("--rpm", [](NewSceneOptions& o) { o.rpm = "30"; });
    refused("--rpm", [](NewSceneOptions& o) { o.rotate_about = "z", o.rpm = "-5"; });
    refused("--material", [](NewSceneOptions& o) { o.material = "wood"; });
    refused("--shot-diameter", [](NewSceneOptions& o) { o.shot_diameter = "-1 mm"; });
    refused("--shot-diameter", [](NewSceneOptions& o) { o.shot_diameter = "2 kg"; });
    refused("-o", [&](NewSceneOptions& o) { o.scene_path = (dir.path / "x.txt").string(); });
    refused("PART: no such file (looked for " + (dir.path / "missing.stl").string() + ")",
            [&](NewSceneOptions& o) { o.part_path = (dir.path / "missing.stl").string(); });
}

}  // namespace
}  // namespace peensim
