// A component whose mesh is a STEP or IGES file (common/cad_file.h): its `tessellation` is read
// (the schema's defaults when left out), a `mesh_unit` beside it is refused (the file states its
// unit), `tessellation` on a mesh file is refused, and the resolved scene reads back the same.
// The parser does not open the mesh files: an empty .step file stands for a part here.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "common/cad_file.h"
#include "common/input_error.h"
#include "scene/resolved_writer.h"
#include "scene/scene_parser.h"
#include "support/temp_dir.h"

namespace peensim {
namespace {

constexpr double kPi = 3.14159265358979323846;

class SceneCadComponent : public ::testing::Test {
protected:
    SceneCadComponent() { std::ofstream(dir_.path / "part.STEP").flush(); }

    // The scene with `rod_entry` as its third component (line 10).
    std::string scene(const std::string& rod_entry) const {
        const std::string assets = std::string(PEENSIM_SOURCE_DIR) + "/assets/";
        return "process: {duration: 1 s}\n"
               "shot: {count: 10, diameter: 2 mm, density: 7.8 g/cm3}\n"
               "components:\n"
               "  - name: sonotrode\n"
               "    role: sonotrode\n"
               "    mesh: " +
               assets +
               "rod-sonotrode.stl\n"
               "    mesh_unit: mm\n"
               "    vibration: {amplitude: 25 um, frequency: 20 kHz}\n"
               "  - {name: chamber, role: chamber, mesh: " +
               assets + "rod-chamber.stl, mesh_unit: mm}\n" + rod_entry;
    }
    std::string virtual_path() const { return (dir_.path / "scene.yaml").string(); }

    InputError error_of(const std::string& text) const {
        try {
            parse_scene_text(text, virtual_path());
        } catch (const InputError& e) {
            return e;
        }
        ADD_FAILURE() << "no InputError";
        return InputError({}, "", "");
    }

    testing::TempDir dir_;
};

TEST(CadFile, KnownByTheExtensionInAnyCase) {
    for (const char* path : {"a.step", "dir.x/A.STP", "part.iges", "PART.IGS", "b.Step"}) EXPECT_TRUE(is_cad_file(path)) << path;
    for (const char* path : {"a.stl", "step", "dir.step/part", "a.step.stl", "a.obj", ""}) EXPECT_FALSE(is_cad_file(path)) << path;
    EXPECT_TRUE(is_iges_file("x.IgEs"));
    EXPECT_FALSE(is_iges_file("x.step"));
}

TEST_F(SceneCadComponent, TessellationTakesTheSchemaDefaultsAndTheGivenValues) {
    const SceneDescription plain = parse_scene_text(scene("  - {name: rod, role: part, mesh: part.STEP}\n"), virtual_path());
    EXPECT_DOUBLE_EQ(plain.components[2].tessellation.chordal_m, 0.01e-3);
    EXPECT_DOUBLE_EQ(plain.components[2].tessellation.angular_rad, 5.0 * kPi / 180.0);
    EXPECT_DOUBLE_EQ(plain.components[2].mesh_unit_m, 1.0);  // the reader's metres
    const SceneDescription given = parse_scene_text(
        scene("  - {name: rod, role: part, mesh: part.STEP, tessellation: {chordal: 3 um, angular: 2 deg}}\n"), virtual_path());
    EXPECT_DOUBLE_EQ(given.components[2].tessellation.chordal_m, 3e-6);
    EXPECT_DOUBLE_EQ(given.components[2].tessellation.angular_rad, 2.0 * kPi / 180.0);

    // The resolved scene states the tessellation (and no mesh_unit) and reads back the same.
    const std::string resolved = resolved_scene_yaml(given);
    const SceneDescription again = parse_scene_text(resolved, virtual_path());
    EXPECT_EQ(again.components[2].tessellation.chordal_m, given.components[2].tessellation.chordal_m);
    EXPECT_EQ(again.components[2].tessellation.angular_rad, given.components[2].tessellation.angular_rad);
    EXPECT_EQ(resolved_scene_yaml(again), resolved);
}

TEST_F(SceneCadComponent, MeshUnitOnAStepFileIsRefused) {
    const InputError e = error_of(scene("  - {name: rod, role: part, mesh: part.STEP, mesh_unit: mm}\n"));
    EXPECT_EQ(e.field(), "components[2].mesh_unit");
    EXPECT_EQ(e.where().line, 10);
    EXPECT_NE(e.problem().find("mesh_unit does not apply to a STEP or IGES file"), std::string::npos) << e.what();
    EXPECT_NE(e.problem().find("states its own length unit"), std::string::npos) << e.what();
}

TEST_F(SceneCadComponent, TessellationOnAMeshFileIsRefused) {
    const std::string stl = std::string(PEENSIM_SOURCE_DIR) + "/assets/rod.stl";
    const InputError e =
        error_of(scene("  - {name: rod, role: part, mesh: " + stl + ", mesh_unit: mm, tessellation: {chordal: 0.01 mm}}\n"));
    EXPECT_EQ(e.field(), "components[2].tessellation");
    EXPECT_NE(e.problem().find("tessellation is only for STEP and IGES files"), std::string::npos) << e.what();
}

TEST_F(SceneCadComponent, ToleranceOutsideItsRangeIsRefused) {
    // A plain number is metres: 0.01 m = 10 mm of chordal error, past the 1 mm sanity limit.
    const InputError e = error_of(scene("  - {name: rod, role: part, mesh: part.STEP, tessellation: {chordal: 0.01}}\n"));
    EXPECT_EQ(e.field(), "components[2].tessellation.chordal");
    const InputError a = error_of(scene("  - {name: rod, role: part, mesh: part.STEP, tessellation: {angular: 60 deg}}\n"));
    EXPECT_EQ(a.field(), "components[2].tessellation.angular");
}

}  // namespace
}  // namespace peensim
