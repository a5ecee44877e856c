// The catalogue of assembly mistakes users made that passed `check` and ran with exit 0: each is
// now an error (or a warning) naming the component, where it is, and what to check; and a sound
// assembly passes without a word. The scenes are the test scene (a 20 mm box chamber closed by a
// plate sonotrode at z = 0, its ceiling at z = 20 mm) with a part placed wrongly.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/check/check_job.h"
#include "app/run/run_job.h"
#include "common/parallel_chunks.h"
#include "geometry/box_mesh.h"
#include "geometry/mesh_checks.h"
#include "geometry/stl_writer.h"
#include "model/assembly_checks.h"
#include "model/shot_cavity.h"
#include "scene/scene_parser.h"
#include "support/temp_dir.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

struct Checked {
    AssemblyReport report;
    std::string text;  // every issue, one per line
};

Checked check(const TestScene& scene, const std::string& yaml_path = "") {
    const auto model = yaml_path.empty() ? scene.compile() : compile_model(parse_scene_file(yaml_path));
    Random rng(model->seed);
    ShotCavity cavity(*model, rng);
    Checked c{check_assembly(*model, &cavity), ""};
    for (const AssemblyIssue& i : c.report.issues) c.text += (i.error ? "error: " : "warning: ") + i.field + ": " + i.message + "\n";
    return c;
}

TestSceneSpec with_box(const Vec3& centre_m, const Vec3& size_m = Vec3(4e-3, 4e-3, 4e-3)) {
    TestSceneSpec spec;
    spec.amplitude_m = 25e-6;
    PartSpec box;
    box.shape = PartShape::box;
    box.size_m = size_m;
    box.center_m = centre_m;
    spec.part = box;
    return spec;
}

// The scene with one more component (yaml lines appended to its components list).
std::string with_extra_component(const TestScene& scene, const std::string& component_yaml) {
    const fs::path path = fs::path(scene.directory()) / "scene-extra.yaml";
    std::ofstream(path) << scene.yaml() << component_yaml;
    return path.string();
}

TEST(AssemblyChecks, ASoundAssemblyPassesWithoutAWord) {
    const TestScene scene(small_rod_scene("event", 0.1));
    const Checked c = check(scene);
    EXPECT_TRUE(c.report.issues.empty()) << c.text;
    EXPECT_GT(c.report.components[2].reachable_fraction, 0.75);  // the end caps, 2 mm from the walls, have no room for a 2 mm shot
    EXPECT_NEAR(c.report.components[2].clearance_to_sonotrode_m, 5e-3 - 25e-6, 1e-6);  // rod r 3 mm, axis 8 mm up
}

TEST(AssemblyChecks, APartWhollyOutsideTheChamberIsAnError) {
    const TestScene scene(with_box(Vec3(0.0, 0.0, 60e-3)));  // 40 mm above the ceiling
    const Checked c = check(scene);
    EXPECT_EQ(c.report.errors(), 1u) << c.text;
    EXPECT_NE(c.text.find("components[2]: part 'part': no part of its surface can be reached by the shot"), std::string::npos) << c.text;
    EXPECT_NE(c.text.find("it spans (-2, -2, 58) mm to (2, 2, 62) mm"), std::string::npos) << c.text;
}

TEST(AssemblyChecks, APartInTheSonotrodeIsAnError) {
    const TestScene scene(with_box(Vec3(0.0, 0.0, 1e-3)));  // from -1 mm to 3 mm: through the plate's face
    const Checked c = check(scene);
    EXPECT_NE(c.text.find("components[2]: part 'part': intersects the sonotrode near"), std::string::npos) << c.text;
}

TEST(AssemblyChecks, APartWithinTheSonotrodesTravelIsAnError) {
    const TestScene scene(with_box(Vec3(0.0, 0.0, 2e-3 + 10e-6)));  // 10 um above the plate at rest, A0 25 um
    const Checked c = check(scene);
    EXPECT_NE(c.text.find("intersects the sonotrode within its vibration travel (+-A0)"), std::string::npos) << c.text;
}

TEST(AssemblyChecks, APartThroughTheLidIsAWarningAndAnErrorWhenStrict) {
    const TestScene scene(with_box(Vec3(0.0, 0.0, 20e-3)));  // half above the ceiling
    const Checked c = check(scene);
    EXPECT_EQ(c.report.errors(), 0u) << c.text;
    EXPECT_EQ(c.report.warnings(), 1u) << c.text;
    EXPECT_NE(c.text.find("warning: components[2]: part 'part': passes through the wall of components[1] (chamber)"), std::string::npos)
        << c.text;
    std::ostringstream out, err;
    EXPECT_EQ(check_job(scene.scene_path(), {}, false, out, err), kExitOk) << err.str();
    EXPECT_NE(err.str().find("warning: "), std::string::npos);
    std::ostringstream out2, err2;
    EXPECT_EQ(check_job(scene.scene_path(), {}, true, out2, err2), kExitInputError);
    EXPECT_NE(err2.str().find("(an error with --strict)"), std::string::npos) << err2.str();
}

// The scene with a second part, the same box moved 1 mm sideways: the two overlap.
std::string with_overlapping_second_part(const TestScene& scene) {
    return with_extra_component(scene,
                                "  - name: second\n"
                                "    role: part\n"
                                "    mesh: part.stl\n"
                                "    mesh_unit: mm\n"
                                "    material: copper\n"
                                "    translation: [1 mm, 1 mm, 0]\n");
}

TEST(AssemblyChecks, TwoOverlappingPartsAreAnError) {
    const TestScene scene(with_box(Vec3(0.0, 0.0, 10e-3)));
    const std::string path = with_overlapping_second_part(scene);
    const Checked c = check(scene, path);
    EXPECT_NE(c.text.find("components[2]: part 'part': intersects components[3] (second)"), std::string::npos) << c.text;
}

// The checks run chunk by chunk on every core: the same clearances to the bit and the same first
// crossing (in triangle order) as on one thread, for a part beside a second one overlapping it.
TEST(AssemblyChecks, TheSameReportOnOneThreadAsOnEveryCore) {
    const TestScene scene(with_box(Vec3(0.0, 0.0, 10e-3)));
    const std::string path = with_overlapping_second_part(scene);
    set_analysis_threads(1);
    const Checked one = check(scene, path);
    set_analysis_threads(0);
    const Checked every = check(scene, path);
    EXPECT_NE(one.text.find(" near ("), std::string::npos) << one.text;
    EXPECT_EQ(one.text, every.text);
    ASSERT_EQ(one.report.issues.size(), every.report.issues.size());
    for (std::size_t k = 0; k < one.report.issues.size(); ++k) EXPECT_EQ(one.report.issues[k].at_m, every.report.issues[k].at_m) << k;
    ASSERT_EQ(one.report.components.size(), every.report.components.size());
    const auto same = [](double x, double y) { return (std::isnan(x) && std::isnan(y)) || x == y; };  // NaN: not measured (no part)
    int parts = 0;
    for (std::size_t k = 0; k < one.report.components.size(); ++k) {
        const ComponentFacts &a = one.report.components[k], &b = every.report.components[k];
        parts += std::isfinite(a.clearance_to_sonotrode_m) ? 1 : 0;
        EXPECT_TRUE(same(a.clearance_to_sonotrode_m, b.clearance_to_sonotrode_m)) << k;
        EXPECT_TRUE(same(a.clearance_to_chamber_m, b.clearance_to_chamber_m)) << k;
    }
    EXPECT_EQ(parts, 2);
}

TEST(AssemblyChecks, ARotatingPartSweepingThroughTheSonotrodeIsAnError) {
    TestSceneSpec spec = with_box(Vec3(0.0, 0.0, 8e-3));
    // Turning about an axis 4 mm up: its corners sweep down to 4 - hypot(2, 6) < 0 mm.
    spec.part->speed_rad_per_s = 10.0;
    spec.part->axis_point_m = Vec3(0.0, 0.0, 4e-3);
    spec.part->axis_direction = Vec3::UnitY();
    const TestScene scene(spec);
    const Checked c = check(scene);
    EXPECT_NE(c.text.find("components[2].motion: part 'part': turning, it sweeps through components[0] (sonotrode)"), std::string::npos)
        << c.text;
    EXPECT_NE(c.text.find("check motion.axis_point"), std::string::npos) << c.text;
}

TEST(AssemblyChecks, ARotatingPartTurningClearIsFine) {
    TestSceneSpec spec = with_box(Vec3(0.0, 0.0, 10e-3));
    spec.part->speed_rad_per_s = 10.0;
    spec.part->axis_point_m = Vec3(0.0, 0.0, 10e-3);
    spec.part->axis_direction = Vec3::UnitY();
    const TestScene scene(spec);
    const Checked c = check(scene);
    EXPECT_TRUE(c.report.issues.empty()) << c.text;
}

TEST(AssemblyChecks, APartWithAMissingCapIsAnError) {
    const TestScene scene(with_box(Vec3(0.0, 0.0, 10e-3)));
    BoxSpec open;
    open.size_m = Vec3(4e-3, 4e-3, 4e-3);
    open.center_m = Vec3(0.0, 0.0, 10e-3);
    write_binary_stl(box_open(open, BoxFace::plus_z, Facing::outward), (fs::path(scene.directory()) / "part.stl").string(), 1e-3, "part");
    const Checked c = check(scene);
    EXPECT_NE(c.text.find("components[2].mesh: part 'part': the mesh is open (4 boundary edges) and shot can reach an opening"),
              std::string::npos)
        << c.text;
}

// A hole in a side wall, not a cap: the opening's own points lie on the surface, where the cavity
// cannot tell its side; the shot centres beside it can (this one was passed as sound).
TEST(AssemblyChecks, APartWithAHoleInItsSideIsAnError) {
    const TestScene scene(with_box(Vec3(0.0, 0.0, 10e-3)));
    BoxSpec spec;
    spec.size_m = Vec3(4e-3, 4e-3, 4e-3);
    spec.center_m = Vec3(0.0, 0.0, 10e-3);
    TriangleMesh holed = box(spec);
    for (std::size_t t = 0; t < holed.triangle_count(); ++t) {
        if (!(triangle_normal(holed, t).x() > 0.5)) continue;  // the first triangle of the +x face
        holed.triangles.erase(holed.triangles.begin() + static_cast<std::ptrdiff_t>(t));
        if (holed.source_facet.size() > t) holed.source_facet.erase(holed.source_facet.begin() + static_cast<std::ptrdiff_t>(t));
        if (holed.group_of_triangle.size() > t)
            holed.group_of_triangle.erase(holed.group_of_triangle.begin() + static_cast<std::ptrdiff_t>(t));
        break;
    }
    ASSERT_EQ(holed.triangle_count(), 11u);
    write_binary_stl(holed, (fs::path(scene.directory()) / "part.stl").string(), 1e-3, "part");
    const Checked c = check(scene);
    EXPECT_NE(c.text.find("components[2].mesh: part 'part': the mesh is open (3 boundary edges) and shot can reach an opening near"),
              std::string::npos)
        << c.text;
}

TEST(AssemblyChecks, ARunRefusesAnAssemblyWithAnError) {
    const TestScene scene(with_box(Vec3(0.0, 0.0, 1e-3)));
    RunOptions o;
    o.scene_path = scene.scene_path();
    o.output_dir = scene.make_subdirectory("out");
    o.progress = false;
    std::ostringstream out, err;
    EXPECT_EQ(run_job(o, out, err), kExitInputError);
    EXPECT_NE(err.str().find("intersects the sonotrode"), std::string::npos) << err.str();
    EXPECT_FALSE(fs::exists(fs::path(o.output_dir) / "summary.json"));
}

// A shot too large for the gaps is refused for that, with the gap and the diameter, not as a
// misplaced part or a missing chamber (issue 28: "check its translation, rotation and mesh_unit",
// "found nothing above its upper face" misled).
std::string refusal_of(const std::string& scene_path, const std::vector<std::string>& overrides, const std::string& out_dir) {
    RunOptions o;
    o.scene_path = scene_path;
    o.output_dir = out_dir;
    o.overrides = overrides;
    o.progress = false;
    std::ostringstream out, err;
    EXPECT_EQ(run_job(o, out, err), kExitInputError) << err.str();
    return err.str();
}

TEST(AssemblyChecks, AShotWiderThanTheGapUnderThePartSaysSo) {
    // The rod scene's rod is 15 mm over the sonotrode and held by the chamber's walls at its ends.
    const TestScene scene(small_rod_scene("event", 0.01));
    const std::string err = refusal_of(std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml", {"shot.diameter=19.9 mm", "shot.count=1"},
                                       scene.make_subdirectory("out"));
    EXPECT_NE(
        err.find("part 'rod': only 12 % of its surface can be reached by the shot: the shot (19.9 mm) is wider than the gap between it and "
                 "the sonotrode (15 mm)"),
        std::string::npos)
        << err;
    EXPECT_EQ(err.find("check its translation"), std::string::npos) << err;
}

TEST(AssemblyChecks, AShotThatFitsNowhereOnTheSonotrodeSaysSo) {
    // A plate 16 x 16 mm hung 2 mm over the sonotrode, 2 mm from the walls: no room for 3 mm shot.
    TestSceneSpec spec = with_box(Vec3(0.0, 0.0, 4e-3), Vec3(16e-3, 16e-3, 4e-3));
    spec.shot_diameter_m = 3e-3;
    const TestScene scene(spec);
    const std::string err = refusal_of(scene.scene_path(), {}, scene.make_subdirectory("out"));
    EXPECT_NE(
        err.find(
            "shot.diameter: the shot (3 mm) does not fit anywhere over the sonotrode's upper face: the widest room there fits a shot of "),
        std::string::npos)
        << err;
    EXPECT_EQ(err.find("found nothing above"), std::string::npos) << err;
}

// Plausibility: values a valid scene may hold by a slip are warnings naming what was meant.
std::string setup_warnings_of(const std::string& scene_path, const std::vector<std::string>& overrides) {
    std::ostringstream out, err;
    const int code = check_job(scene_path, overrides, false, out, err);
    EXPECT_EQ(code, kExitOk) << err.str();
    return err.str();
}

std::string setup_warnings(const TestScene& scene, const std::vector<std::string>& overrides) {
    return setup_warnings_of(scene.scene_path(), overrides);
}

TEST(SetupPlausibility, AnAmplitudeWithoutItsUnitIsNamed) {
    const TestScene scene(small_rod_scene("event", 0.1));
    const std::string w = setup_warnings(scene, {"components[sonotrode].vibration.amplitude=25"});
    EXPECT_NE(w.find("components[0].vibration.amplitude: the plain number 25 is read in SI units: 25 m, while this scene gives "
                     "units elsewhere; did you mean 25 um?"),
              std::string::npos)
        << w;
    EXPECT_NE(w.find("A0 2.5e+04 mm is far above ultrasonic peening's 10-100 um"), std::string::npos) << w;
    std::ostringstream out, err;
    EXPECT_EQ(check_job(scene.scene_path(), {"components[sonotrode].vibration.amplitude=25"}, true, out, err), kExitInputError);
}

// A file all in SI (a resolved scene, as the report's command and a Python sweep of a dict run it)
// stays quiet when an override writes a unit: its plain numbers are not slips.
TEST(SetupPlausibility, AnSiFileIsNotBlamedForAUnitInAnOverride) {
    peensim::testing::TempDir dir;
    std::ostringstream out, err;
    ASSERT_EQ(check_job(std::string(PEENSIM_SOURCE_DIR) + "/scenes/gear.yaml", {}, false, out, err), kExitOk) << err.str();
    const std::string text = out.str();
    const fs::path resolved = dir.path / "resolved.yaml";
    std::ofstream(resolved) << text.substr(text.find("# Resolved scene"));
    EXPECT_EQ(setup_warnings_of(resolved.string(), {"process.duration=1164 s", "components[gear].motion=static"}), "");
    // A plain number in an override, in a scene written with units, still is.
    EXPECT_NE(
        setup_warnings_of(std::string(PEENSIM_SOURCE_DIR) + "/scenes/gear.yaml", {"shot.diameter=0.002"}).find("the plain number 0.002"),
        std::string::npos);
}

TEST(SetupPlausibility, FrequencyGravityShotSizeAndMeshUnitOutsideTheWindow) {
    const TestScene scene(small_rod_scene("event", 0.1));
    EXPECT_NE(setup_warnings(scene, {"components[sonotrode].vibration.frequency=20"}).find("20 Hz is outside 1-100 kHz"),
              std::string::npos);
    // A hint only where the number in the usual unit lands in the window.
    EXPECT_NE(setup_warnings(scene, {"components[sonotrode].vibration.frequency=20"}).find("did you mean 20 kHz?"), std::string::npos);
    EXPECT_NE(setup_warnings(scene, {"components[sonotrode].vibration.frequency=20000 kHz"}).find("did you mean 2e+04 Hz?"),
              std::string::npos);
    const std::string at_200khz = setup_warnings(scene, {"components[sonotrode].vibration.frequency=200 kHz"});
    EXPECT_NE(at_200khz.find("2e+05 Hz is outside 1-100 kHz"), std::string::npos) << at_200khz;
    EXPECT_EQ(at_200khz.find("did you mean"), std::string::npos) << at_200khz;
    const std::string at_2mm = setup_warnings(scene, {"components[sonotrode].vibration.amplitude=2 mm"});
    EXPECT_NE(at_2mm.find("A0 2 mm is far above"), std::string::npos) << at_2mm;
    EXPECT_EQ(at_2mm.find("did you mean"), std::string::npos) << at_2mm;
    EXPECT_NE(setup_warnings(scene, {"process.gravity=[0, 0, -98.1]"}).find("98.1 m/s2: expected ~9.81 m/s2"), std::string::npos);
    EXPECT_EQ(setup_warnings(scene, {"process.gravity=[0, 0, 0]"}).find("gravity"), std::string::npos);  // weightless is fine
    EXPECT_NE(setup_warnings(scene, {"shot.count=1", "shot.diameter=2.5 mm"}).find("more than a tenth of it"), std::string::npos);
    // The test scene's meshes are in mm: read as metres, the chamber (walls included) is 25 m across.
    std::ostringstream out, err;
    check_job(scene.scene_path(), {"components[chamber].mesh_unit=m", "components[sonotrode].mesh_unit=m", "components[part].mesh_unit=m"},
              false, out, err);
    EXPECT_NE(
        err.str().find(
            "'chamber' is 25 m across (1 m per file unit): implausible for a peening chamber; in mm it would be 25 mm (mesh_unit: mm)"),
        std::string::npos)
        << err.str();
}

TEST(SetupPlausibility, TheShippedScenesPassWithoutAWarning) {
    for (const char* name : {"rod.yaml", "gear.yaml", "rotating-gear.yaml", "almen.yaml"}) {
        std::ostringstream out, err;
        EXPECT_EQ(check_job(std::string(PEENSIM_SOURCE_DIR) + "/scenes/" + name, {}, true, out, err), kExitOk) << name << ": " << err.str();
        EXPECT_EQ(err.str(), "") << name;
    }
}

}  // namespace
}  // namespace peensim::testing
