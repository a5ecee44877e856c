// The catalogue of bad scene files (tests/scenes_bad/*.yaml): each one is refused with a message
// that names the file, the line, the field and what was expected. Never a crash.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <set>
#include <sstream>
#include <string>

#include "common/input_error.h"
#include "model/model.h"
#include "scene/scene_parser.h"

namespace peensim {
namespace {

const std::string bad_dir = std::string(PEENSIM_SOURCE_DIR) + "/tests/scenes_bad";

struct BadScene {
    const char* file;
    int line;              // 1-based line the message must point at
    const char* field;     // "" when no field applies (YAML syntax)
    const char* expected;  // a phrase of what was expected
};

// gtest's own printer would dump the case's bytes, unset ones among them (valgrind reports them
// as uninitialised at every start of the test binary).
void PrintTo(const BadScene& b, std::ostream* os) { *os << b.file; }

const BadScene catalogue[] = {
    {"unknown_key.yaml", 3, "shot.densty", "unknown key 'densty' in shot; valid keys: count, diameter, sizes, fractions_by, density"},
    {"negative_diameter.yaml", 3, "shot.diameter", "expected a length in (0, 0.02] m, got '-2 mm'"},
    {"unit_typo.yaml", 3, "shot.diameter", "unknown unit 'mmm'"},
    {"wrong_dimension.yaml", 11, "components[0].vibration.amplitude", "'kHz' is a unit of frequency, but a length"},
    {"missing_mesh.yaml", 14, "components[1].mesh", "mesh file not found"},
    {"unknown_material.yaml", 10, "components[0].material", "unknown material 'unobtainium'; expected one of"},
    {"missing_required.yaml", 2, "process.duration", "missing required key 'duration'"},
    {"wrong_type.yaml", 16, "output.log", "expected a list of names"},
    {"bad_syntax.yaml", 2, "", "invalid YAML"},
    {"duplicate_component.yaml", 15, "components[2].name", "duplicate component name 'chamber'"},
    {"no_chamber.yaml", 6, "components", "expected at least one chamber"},
    {"vibration_on_chamber.yaml", 15, "components[1].vibration", "vibration is only for the sonotrode"},
    {"shot_shot_friction.yaml", 16, "contacts.shot-shot.f", "not a parameter of law 'impulse' between shot; expected law, C0, V0"},
    {"contact_unknown_material.yaml", 16, "contacts.shot-steel", "unknown contact pair 'shot-steel'"},
    {"zero_axis.yaml", 11, "components[0].vibration.axis", "expected a direction, got the zero vector"},
    {"density_and_material.yaml", 3, "shot.material", "either shot.density or shot.material, not both"},
    {"rpm_for_part_not_rotating.yaml", 18, "components[2].motion", "a rotating motion is only for role part"},
    {"count_not_integer.yaml", 3, "shot.count", "expected a whole number"},
    {"almen_half_calibration.yaml", 18, "components[2].almen.dose_constant",
     "the arc-height calibration needs both saturation_arc_height and dose_constant"},
    {"almen_on_part.yaml", 18, "components[2].almen", "almen is only for role almen"},
    {"almen_two_calibrations.yaml", 21, "components[2].almen.calibration",
     "give either calibration (the predictive model) or saturation_arc_height and dose_constant (the dose model), not both"},
    {"almen_calibration_missing_key.yaml", 19, "components[2].almen.calibration.covering_rate", "missing required key 'covering_rate'"},
    {"impact_speed_zero.yaml", 3, "accuracy.impact_speed", "expected a speed > 0 m/s, got '0 m/s'"},
    {"impact_speed_negative.yaml", 3, "accuracy.impact_speed", "expected a speed > 0 m/s, got '-5 cm/s'"},
    {"impact_speed_not_a_speed.yaml", 3, "accuracy.impact_speed", "'cm' is a unit of length, but a speed"},
    {"rotating_without_axis_point.yaml", 19, "components[2].motion.axis_point", "missing required key 'axis_point'"},
    {"region_count_wraps.yaml", 19, "components[2].regions[0].sectors.count", "expected a whole number in [1, 3600], got '4294967296'"},
    {"travel_fraction_tiny.yaml", 3, "accuracy.travel_fraction", "in [0.001, 1]"},
    {"drag_with_event.yaml", 3, "accuracy.scheme", "the event scheme needs exact parabolic flights, and air.drag is on; expected `step`"},
    {"soft_with_drag.yaml", 3, "accuracy.scheme", "the soft scheme needs exact parabolic flights, and air.drag is on; expected `step`"},
    {"poisson_ratio_above_half.yaml", 5, "materials.steel.poisson_ratio", "expected a number in [-0.99, 0.5], got '3.5'"},
    {"air_viscosity_wrong_unit.yaml", 6, "air.viscosity",
     "unknown unit 'm2/s' in '1.5e-5 m2/s' for a dynamic viscosity; accepted units: Pa s"},
    {"count_zero_without_sources.yaml", 3, "shot.count", "expected at least 1 shot, or sources that emit them"},
    {"sink_box_inverted.yaml", 14, "sinks[0].max", "expected max > min in x, y and z"},
    {"shot_without_sonotrode.yaml", 4, "components", "no component has role sonotrode, and shot.count is 10"},
    {"source_sink_same_name.yaml", 11, "sinks[0].name", "duplicate name 'nozzle'; source and sink names must be unique"},
    {"sink_box_with_mesh.yaml", 15, "sinks[0].mesh", "'mesh' is only for region mesh"},
    {"nozzle_position_and_target.yaml", 12, "sources[0].position", "'position' and `target` both place the nozzle: expected one"},
    {"nozzle_rate_and_mass_flow.yaml", 14, "sources[0].mass_flow", "expected `rate` or `mass_flow`, not both"},
    {"hopper_with_speed.yaml", 13, "sources[0].speed",
     "'speed' is a nozzle's; a hopper drops its shot at rest from `opening_min` to `opening_max`"},
    {"hopper_without_opening.yaml", 9, "sources[0]", "missing required key 'opening_max' (a hopper's opening)"},
    {"hopper_opening_inverted.yaml", 12, "sources[0].opening_max", "expected opening_max >= opening_min in x, y and z"},
    {"nozzle_with_opening.yaml", 12, "sources[0].opening_min", "'opening_min' is only for kind hopper"},
    {"nozzle_target_without_distance.yaml", 9, "sources[0]", "missing required key 'distance' (a nozzle placed by its target)"},
    {"render_frames_unbounded.yaml", 18, "render.slow_motion", "the render block plans 300000000 frames"},
    {"shot_sizes_not_summing.yaml", 6, "shot.sizes", "expected the fractions to sum to 1 (within 0.005), got 0.9"},
    {"shot_diameter_and_sizes.yaml", 7, "shot.sizes", "give either shot.diameter (one size) or shot.sizes (a mix), not both"},
    {"shot_sizes_duplicate.yaml", 8, "shot.sizes[1].diameter", "this diameter is already in the mix; give each size once"},
    {"initial_speed_too_fast.yaml", 3, "shot.initial_speed", "expected a speed in [0, 1000] m/s, got '1e6 m/s'"},
    {"initial_velocity_too_fast.yaml", 3, "shot.initial_velocity", "expected a velocity of at most 1000 m/s, got 1e+06 m/s"},
    {"nested_too_deep.yaml", 2, "", "invalid YAML: maps and lists nested deeper than 64 levels"},
};

// Scenes that read but cannot be compiled into a model (compile_model: a law without what it
// needs, a scheme without the laws it integrates).
const BadScene compile_catalogue[] = {
    {"soft_with_impulse_law.yaml", 9, "contacts.default.law",
     "expected a soft-sphere law ('hertz-mindlin', 'linear-spring-dashpot') for shot-shot"},
    {"sink_mesh_open.yaml", 13, "sinks[0].mesh", "a mesh sink must be a closed mesh"},  // its mesh: line
    {"air_jet_without_drag.yaml", 9, "sources[0].air_speed",
     "an air jet acts on the shot through drag (or rebound scatter), both off; expected air.drag: sphere"},
    {"soft_with_rebound_scatter.yaml", 5, "air.rebound_scatter",
     "the soft scheme integrates contact forces, which rebound scatter cannot turn"},
    {"soft_without_youngs_modulus.yaml", 9, "contacts.default.law", "add materials.titanium.youngs_modulus and .poisson_ratio"},
    {"soft_with_shot_mix.yaml", 4, "shot.sizes", "the soft scheme's Hertz-Mindlin pairs are built for one shot size"},
};

void expect_refusal(const BadScene& bad, const std::string& path, const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.where().file, path) << msg;
    EXPECT_EQ(e.where().line, bad.line) << msg;
    EXPECT_GT(e.where().column, 0) << msg;
    EXPECT_NE(msg.find(std::string(bad.file) + ":" + std::to_string(bad.line) + ":"), std::string::npos) << msg;
    EXPECT_EQ(e.field(), bad.field) << msg;
    if (*bad.field != '\0') {
        EXPECT_NE(msg.find(std::string(": ") + bad.field + ": "), std::string::npos) << msg;
    }
    EXPECT_NE(msg.find(bad.expected), std::string::npos) << msg;
}

class SceneBadFiles : public ::testing::TestWithParam<BadScene> {};

TEST_P(SceneBadFiles, IsRefusedWithFileLineFieldAndExpectation) {
    const BadScene& bad = GetParam();
    const std::string path = bad_dir + "/" + bad.file;
    try {
        parse_scene_file(path);
        FAIL() << bad.file << " was accepted";
    } catch (const InputError& e) {
        expect_refusal(bad, path, e);
    }
}

class SceneBadModels : public ::testing::TestWithParam<BadScene> {};

TEST_P(SceneBadModels, ReadsButIsRefusedByTheModelWithFileLineFieldAndExpectation) {
    const BadScene& bad = GetParam();
    const std::string path = bad_dir + "/" + bad.file;
    try {
        (void)compile_model(parse_scene_file(path));
        FAIL() << bad.file << " was accepted";
    } catch (const InputError& e) {
        expect_refusal(bad, path, e);
    }
}

INSTANTIATE_TEST_SUITE_P(Catalogue, SceneBadFiles, ::testing::ValuesIn(catalogue), [](const ::testing::TestParamInfo<BadScene>& info) {
    std::string name = info.param.file;
    name = name.substr(0, name.find('.'));
    for (char& c : name)
        if (c == '-') c = '_';
    return name;
});
INSTANTIATE_TEST_SUITE_P(ModelCatalogue, SceneBadModels, ::testing::ValuesIn(compile_catalogue),
                         [](const ::testing::TestParamInfo<BadScene>& info) {
                             std::string name = info.param.file;
                             name = name.substr(0, name.find('.'));
                             for (char& c : name)
                                 if (c == '-') c = '_';
                             return name;
                         });

// Each bad file is the same small scene with one thing broken; the unbroken scene parses.
TEST(SceneBadFilesCatalogue, TheUnbrokenSceneParses) {
    const std::string text = R"(# The scene every bad file breaks in one place.
process: {duration: 1 s}
shot: {count: 10, diameter: 2 mm, density: 7.8 g/cm3}
materials:
  titanium: {density: 4.5 g/cm3}
components:
  - name: sonotrode
    role: sonotrode
    mesh: tetrahedron.stl
    material: titanium
    vibration: {amplitude: 25 um, frequency: 20 kHz}
  - name: chamber
    role: chamber
    mesh: tetrahedron.stl
)";
    const SceneDescription s = parse_scene_text(text, bad_dir + "/unbroken.yaml");
    EXPECT_EQ(s.shot.sizes.front().diameter_m, 0.002);
    EXPECT_EQ(s.components.size(), 2u);
}

TEST(SceneBadFilesCatalogue, EveryFileInTheFolderIsInTheCatalogue) {
    std::set<std::string> listed;
    for (const BadScene& bad : catalogue) listed.insert(bad.file);
    for (const BadScene& bad : compile_catalogue) listed.insert(bad.file);
    for (const auto& entry : std::filesystem::directory_iterator(bad_dir)) {
        if (entry.path().extension() != ".yaml") continue;
        EXPECT_TRUE(listed.count(entry.path().filename().string())) << entry.path() << " is not checked";
    }
    EXPECT_EQ(listed.size(), std::size(catalogue) + std::size(compile_catalogue));
}

}  // namespace
}  // namespace peensim
