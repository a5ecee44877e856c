// Scene files -> SceneDescription: SI values, defaults, --set overrides, the resolved scene.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>

#include "common/input_error.h"
#include "scene/resolved_writer.h"
#include "scene/scene_difference.h"
#include "scene/scene_parser.h"
#include "support/files.h"
#include "support/temp_dir.h"

namespace peensim {
namespace {

constexpr double pi = std::numbers::pi;

// Scenes given as text are placed in tests/scenes_bad/, next to its small tetrahedron mesh.
const std::string scene_dir = std::string(PEENSIM_SOURCE_DIR) + "/tests/scenes_bad";
const std::string virtual_path = scene_dir + "/inline.yaml";

const char* const full_scene = R"(
name: gear case study
process:   {duration: 5 s, gravity: [0, 0, -9.81], seed: 3}
accuracy:  {travel_fraction: 0.2, scheme: step}
shot:
  count: 512
  diameter: 2 mm
  material: steel
  initial_speed: 2 m/s
materials:
  steel: {density: 7.8 g/cm3}
  titanium: {density: 4.5 g/cm3, yield_stress: 1.1 GPa}
  aluminium-2000: {yield_stress: 300 MPa}
contacts:
  shot-shot: {C0: 0.95, V0: 2 m/s}
  shot-titanium: {C0: 0.8, V0: 1.5 m/s, mu: 0.9, f: 0.2}
  default: {C0: 0.85, V0: 0.4 m/s, mu: 0.7, f: 0.15}
components:
  - name: sonotrode
    role: sonotrode
    mesh: tetrahedron.stl
    mesh_unit: mm
    translation: [0, 0, -5 mm]
    rotation: {axis: [1, 0, 0], angle: 90 deg}
    material: titanium
    vibration: {amplitude: 25 um, frequency: 20 kHz, phase: 90 deg, axis: [0, 0, 2]}
  - name: chamber
    role: chamber
    mesh: ./tetrahedron.stl
    translation: "0 0 10 mm"
  - name: gear
    role: part
    mesh: ../scenes_bad/tetrahedron.stl
    material: aluminium-2000
    motion: {type: rotating, axis_point: [0, 0, 40 mm], axis_direction: [0, 3, 0], speed: 30 rpm}
  - name: axle
    role: fixture
    mesh: tetrahedron.stl
    motion: static
output:
  log: [gear, axle]
  directory: out/gear
  checkpoint_interval: 2 min
)";

const char* const minimal_scene = R"(
process: {duration: 0.5}
shot: {count: 3, diameter: 0.001, density: 7800}
components:
  - {name: sono, role: sonotrode, mesh: tetrahedron.stl, vibration: {amplitude: 30 um, frequency: 20 kHz}}
  - {name: box, role: chamber, mesh: tetrahedron.stl}
  - {name: rod, role: part, mesh: tetrahedron.stl}
)";

std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
    try {
        parse_scene_text(text, virtual_path, overrides);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

const ComponentDesc& component_named(const SceneDescription& s, const std::string& name) {
    for (const ComponentDesc& k : s.components)
        if (k.name == name) return k;
    throw std::runtime_error("no component " + name);
}

const ContactPairDesc& contact(const SceneDescription& s, const std::string& key) {
    for (const ContactPairDesc& c : s.contacts)
        if (c.key == key) return c;
    throw std::runtime_error("no contact " + key);
}

std::string tetrahedron_path() { return std::filesystem::path(scene_dir + "/tetrahedron.stl").lexically_normal().string(); }

TEST(SceneParser, FullSceneReadsInSI) {
    const SceneDescription s = parse_scene_text(full_scene, virtual_path);
    EXPECT_EQ(s.name, "gear case study");
    EXPECT_EQ(s.source_file, virtual_path);
    EXPECT_EQ(s.process.duration_s, 5.0);
    EXPECT_EQ(s.process.gravity_m_per_s2, Vec3(0, 0, -9.81));
    EXPECT_EQ(s.process.seed, 3u);
    EXPECT_EQ(s.accuracy.travel_fraction, 0.2);
    EXPECT_EQ(s.accuracy.scheme, SteppingScheme::step);

    EXPECT_EQ(s.shot.count, 512);
    EXPECT_EQ(s.shot.sizes.front().diameter_m, 0.002);
    EXPECT_EQ(s.shot.material, "steel");
    EXPECT_EQ(s.shot.density_kg_per_m3, 7800.0);
    EXPECT_EQ(s.shot.initial, InitialVelocityKind::random_upward);
    EXPECT_EQ(s.shot.initial_speed_m_per_s, 2.0);

    ASSERT_EQ(s.materials.size(), 3u);
    EXPECT_EQ(s.materials[1].name, "titanium");
    EXPECT_EQ(*s.materials[1].density_kg_per_m3, 4500.0);
    EXPECT_EQ(*s.materials[1].yield_stress_pa, 1.1e9);
    EXPECT_FALSE(s.materials[2].density_kg_per_m3.has_value());
    EXPECT_EQ(*s.materials[2].yield_stress_pa, 300e6);

    ASSERT_EQ(s.contacts.size(), 3u);
    EXPECT_EQ(contact(s, "shot-shot").value("C0"), 0.95);
    EXPECT_EQ(contact(s, "shot-shot").value("V0"), 2.0);
    EXPECT_EQ(contact(s, "shot-titanium").value("mu"), 0.9);
    EXPECT_EQ(contact(s, "shot-titanium").value("f"), 0.2);
    EXPECT_EQ(contact(s, "default").value("C0"), 0.85);
    EXPECT_EQ(contact(s, "default").value("V0"), 0.4);

    const ComponentDesc& sono = component_named(s, "sonotrode");
    EXPECT_EQ(sono.role, ComponentRole::sonotrode);
    EXPECT_EQ(sono.mesh_path, tetrahedron_path());
    EXPECT_EQ(sono.mesh_unit_m, 1e-3);
    EXPECT_EQ(sono.translation_m, Vec3(0, 0, -0.005));
    EXPECT_TRUE(sono.rotation.isApprox(Eigen::AngleAxisd(pi / 2, Vec3::UnitX()).toRotationMatrix()));
    EXPECT_EQ(sono.material, "titanium");
    ASSERT_TRUE(sono.vibration.has_value());
    EXPECT_EQ(sono.vibration->amplitude_m, 25e-6);
    EXPECT_EQ(sono.vibration->frequency_hz, 20000.0);
    EXPECT_EQ(sono.vibration->phase_rad, pi / 2);
    EXPECT_EQ(*sono.vibration->axis, Vec3(0, 0, 1));  // normalised
    EXPECT_FALSE(sono.rotation_motion.has_value());

    const ComponentDesc& chamber = component_named(s, "chamber");
    EXPECT_EQ(chamber.mesh_path, tetrahedron_path());
    EXPECT_EQ(chamber.translation_m, Vec3(0, 0, 0.01));
    EXPECT_FALSE(chamber.vibration.has_value());

    const ComponentDesc& gear = component_named(s, "gear");
    EXPECT_EQ(gear.mesh_path, tetrahedron_path());
    ASSERT_TRUE(gear.rotation_motion.has_value());
    EXPECT_EQ(gear.rotation_motion->axis_point_m, Vec3(0, 0, 0.04));
    EXPECT_EQ(gear.rotation_motion->axis_direction, Vec3(0, 1, 0));
    EXPECT_EQ(gear.rotation_motion->speed_rad_per_s, pi);
    EXPECT_FALSE(component_named(s, "axle").rotation_motion.has_value());

    EXPECT_EQ(s.output.logged_components, (std::vector<std::string>{"gear", "axle"}));
    EXPECT_EQ(s.output.directory, "out/gear");
    EXPECT_EQ(s.output.checkpoint_interval_s, 120.0);
}

TEST(SceneParser, FieldsRememberWhereTheyCameFrom) {
    const SceneDescription s = parse_scene_text(full_scene, virtual_path);
    EXPECT_EQ(s.shot.where.file, virtual_path);
    EXPECT_EQ(s.shot.where.line, 5);
    EXPECT_EQ(component_named(s, "gear").where.line, 31);
    EXPECT_EQ(component_named(s, "sonotrode").vibration->where.line, 26);
}

TEST(SceneParser, DefaultsAreFilledIn) {
    const SceneDescription s = parse_scene_text(minimal_scene, virtual_path);
    EXPECT_EQ(s.name, "");
    EXPECT_EQ(s.process.gravity_m_per_s2, Vec3(0, 0, -9.81));
    EXPECT_EQ(s.process.seed, 1u);
    EXPECT_EQ(s.accuracy.travel_fraction, 0.25);
    EXPECT_EQ(s.shot.initial, InitialVelocityKind::rest);
    EXPECT_EQ(s.shot.material, "");
    EXPECT_TRUE(s.materials.empty());
    ASSERT_EQ(s.contacts.size(), 1u);
    EXPECT_EQ(s.contacts[0].key, "default");
    EXPECT_EQ(s.contacts[0].value("C0"), 0.9);
    EXPECT_EQ(s.contacts[0].value("V0"), 0.5);
    EXPECT_EQ(s.contacts[0].value("mu"), 0.71);
    EXPECT_EQ(s.contacts[0].value("f"), 0.1);
    const ComponentDesc& sono = component_named(s, "sono");
    EXPECT_EQ(sono.mesh_unit_m, 1.0);
    EXPECT_EQ(sono.translation_m, Vec3::Zero());
    EXPECT_EQ(sono.rotation, Mat3::Identity());
    EXPECT_EQ(sono.material, "");
    EXPECT_EQ(sono.vibration->phase_rad, 0.0);
    EXPECT_FALSE(sono.vibration->axis.has_value());
    EXPECT_EQ(s.output.logged_components, std::vector<std::string>{"rod"});  // every part
    EXPECT_EQ(s.output.directory, "");
    EXPECT_EQ(s.output.checkpoint_interval_s, 60.0);
}

TEST(SceneParser, PairCoefficientsLeftOutTakeTheDefaultPair) {
    const std::string text = std::string(minimal_scene) + R"(
materials: {steel: {}}
contacts:
  shot-steel: {C0: 0.7}
  shot-shot: {V0: 3 m/s}
  default: {C0: 0.6, V0: 0.2, mu: 0.5, f: 0.3}
)";
    const SceneDescription s = parse_scene_text(text, virtual_path);
    ASSERT_EQ(s.contacts.size(), 3u);
    EXPECT_EQ(contact(s, "shot-steel").value("C0"), 0.7);
    EXPECT_EQ(contact(s, "shot-steel").value("V0"), 0.2);
    EXPECT_EQ(contact(s, "shot-steel").value("mu"), 0.5);
    EXPECT_EQ(contact(s, "shot-steel").value("f"), 0.3);
    EXPECT_EQ(contact(s, "shot-shot").value("C0"), 0.6);
    EXPECT_EQ(contact(s, "shot-shot").value("V0"), 3.0);
}

TEST(SceneParser, RotationFormsAgree) {
    const auto rotation_of = [](const std::string& rotation) {
        const std::string text = std::string(minimal_scene) +
                                 "  - {name: r, role: fixture, mesh: tetrahedron.stl, "
                                 "rotation: " +
                                 rotation + "}\n";
        return component_named(parse_scene_text(text, virtual_path), "r").rotation;
    };
    const Mat3 expected = (Eigen::AngleAxisd(pi / 2, Vec3::UnitX()) * Eigen::AngleAxisd(pi / 6, Vec3::UnitZ())).toRotationMatrix();
    EXPECT_TRUE(rotation_of("{euler_xyz: [90, 0, 30]}").isApprox(expected, 1e-15));
    EXPECT_TRUE(rotation_of("{euler_xyz: [90 deg, 0, 0.5235987755982988 rad]}").isApprox(expected, 1e-15));
    EXPECT_TRUE(
        rotation_of("{axis: [0, 0, 1], angle: 90 deg}").isApprox(Eigen::AngleAxisd(pi / 2, Vec3::UnitZ()).toRotationMatrix(), 1e-15));
    EXPECT_EQ(rotation_of("{matrix: [[0, -1, 0], [1, 0, 0], [0, 0, 1]]}"),
              Eigen::AngleAxisd(pi / 2, Vec3::UnitZ()).toRotationMatrix().array().round().matrix());
    EXPECT_NE(error_of(std::string(minimal_scene) +
                       "  - {name: r, role: fixture, mesh: tetrahedron.stl, rotation: {matrix: [[2, 0, 0], [0, 1, 0], "
                       "[0, 0, 1]]}}\n")
                  .find("expected a rotation matrix"),
              std::string::npos);
}

TEST(SceneParser, VectorsAsOneString) {
    const auto translation_of = [](const std::string& t) {
        const std::string text = std::string(minimal_scene) +
                                 "  - {name: t, role: fixture, mesh: tetrahedron.stl, "
                                 "translation: \"" +
                                 t + "\"}\n";
        return component_named(parse_scene_text(text, virtual_path), "t").translation_m;
    };
    EXPECT_EQ(translation_of("0 0 -5 mm"), Vec3(0, 0, -0.005));
    EXPECT_EQ(translation_of("1 2 3"), Vec3(1, 2, 3));
    EXPECT_EQ(translation_of("1 mm 2 cm 3 m"), Vec3(0.001, 0.02, 3));
    EXPECT_EQ(translation_of("1, 2, 3mm"), Vec3(0.001, 0.002, 0.003));
    EXPECT_NE(error_of(std::string(minimal_scene) + "  - {name: t, role: fixture, mesh: tetrahedron.stl, translation: \"1 2\"}\n")
                  .find("expected a vector of 3 numbers"),
              std::string::npos);
}

TEST(SceneParser, OverridesApplyBeforeValidation) {
    const SceneDescription s =
        parse_scene_text(full_scene, virtual_path,
                         {"process.duration=0.2", "process.seed=7", "shot.diameter=1 mm", "components[gear].motion.speed=60 rpm",
                          "components[1].translation=[1 mm, 2 mm, 3 mm]", "output.log=[gear]", "process.gravity=[0,0,-1.62]",
                          "materials.titanium.density=4.43 g/cm3", "contacts.shot-shot.C0=0.5", "name=renamed"});
    EXPECT_EQ(s.process.duration_s, 0.2);
    EXPECT_EQ(s.process.seed, 7u);
    EXPECT_EQ(s.shot.sizes.front().diameter_m, 0.001);
    EXPECT_EQ(component_named(s, "gear").rotation_motion->speed_rad_per_s, 2 * pi);
    EXPECT_EQ(component_named(s, "chamber").translation_m, Vec3(0.001, 0.002, 0.003));
    EXPECT_EQ(s.output.logged_components, std::vector<std::string>{"gear"});
    EXPECT_EQ(s.process.gravity_m_per_s2, Vec3(0, 0, -1.62));
    EXPECT_EQ(*s.materials[1].density_kg_per_m3, 4430.0);
    EXPECT_EQ(contact(s, "shot-shot").value("C0"), 0.5);
    EXPECT_EQ(s.name, "renamed");
}

TEST(SceneParser, OverridesCanAddKeysAndSections) {
    const SceneDescription s =
        parse_scene_text(minimal_scene, virtual_path,
                         {"accuracy.travel_fraction=0.1",
                          "components[rod].motion={type: rotating, axis_point: [0, 0, 0], "
                          "axis_direction: [1, 0, 0], speed: 10 rpm}",
                          "materials.copper.density=8.96 g/cm3", "shot.density=8960", "process.duration=1", "process.duration=2"});
    EXPECT_EQ(s.accuracy.travel_fraction, 0.1);
    ASSERT_TRUE(component_named(s, "rod").rotation_motion.has_value());
    EXPECT_EQ(component_named(s, "rod").rotation_motion->axis_direction, Vec3(1, 0, 0));
    EXPECT_EQ(*s.materials.at(0).density_kg_per_m3, 8960.0);
    EXPECT_EQ(s.process.duration_s, 2.0);  // the last override wins
}

TEST(SceneParser, OverrideOfUnknownPathNamesIt) {
    for (const std::string& bad : {std::string("process.dration=1"), std::string("components[nope].mesh=x"),
                                   std::string("components[9].mesh=x"), std::string("shot.count.x=1")}) {
        try {
            parse_scene_text(minimal_scene, virtual_path, {bad});
            ADD_FAILURE() << bad << " was accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(e.where().file, "<--set>") << e.what();
            EXPECT_EQ(e.field(), bad.substr(0, bad.find('='))) << e.what();
            EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
        }
    }
    EXPECT_NE(error_of(minimal_scene, {"process.dration=1"}).find("valid keys: duration, gravity, seed"), std::string::npos);
    EXPECT_NE(error_of(minimal_scene, {"process.duration"}).find("expected path=value"), std::string::npos);
    EXPECT_NE(error_of(minimal_scene, {"process.duration="}).find("missing value"), std::string::npos);
}

TEST(SceneParser, BadOverriddenValueBlamesTheOverride) {
    try {
        parse_scene_text(minimal_scene, virtual_path, {"components[rod].material=unobtainium"});
        ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where().file, "<--set>");
        EXPECT_EQ(e.field(), "components[2].material");
        EXPECT_NE(e.problem().find("unknown material 'unobtainium'"), std::string::npos) << e.what();
        EXPECT_NE(e.problem().find("from --set 'components[rod].material=unobtainium'"), std::string::npos);
    }
    EXPECT_NE(error_of(minimal_scene, {"shot.diameter=-1 mm"}).find("<--set>: shot.diameter: expected a length"), std::string::npos);
}

TEST(SceneParser, ResolvedSceneReadsBackTheSame) {
    for (const char* text : {full_scene, minimal_scene}) {
        const SceneDescription first = parse_scene_text(text, virtual_path);
        const std::string resolved = resolved_scene_yaml(first);
        // Parsed from elsewhere: mesh paths are absolute now.
        const SceneDescription second = parse_scene_text(resolved, "/nonexistent/dir/resolved.yaml");
        EXPECT_EQ(resolved_scene_yaml(second), resolved);
        EXPECT_EQ(scene_hash(second), scene_hash(first));
        EXPECT_EQ(second.shot.sizes.front().diameter_m, first.shot.sizes.front().diameter_m);
        EXPECT_EQ(second.shot.density_kg_per_m3, first.shot.density_kg_per_m3);
        ASSERT_EQ(second.components.size(), first.components.size());
        for (std::size_t i = 0; i < first.components.size(); ++i) {
            EXPECT_EQ(second.components[i].rotation, first.components[i].rotation);
            EXPECT_EQ(second.components[i].translation_m, first.components[i].translation_m);
            EXPECT_EQ(second.components[i].mesh_path, first.components[i].mesh_path);
            EXPECT_EQ(second.components[i].mesh_unit_m, first.components[i].mesh_unit_m);
        }
        ASSERT_EQ(second.contacts.size(), first.contacts.size());
        for (std::size_t i = 0; i < first.contacts.size(); ++i) {
            EXPECT_EQ(second.contacts[i].key, first.contacts[i].key);
            EXPECT_EQ(second.contacts[i].law, first.contacts[i].law);
            ASSERT_EQ(second.contacts[i].parameters.size(), first.contacts[i].parameters.size());
            for (std::size_t k = 0; k < first.contacts[i].parameters.size(); ++k) {
                EXPECT_EQ(second.contacts[i].parameters[k].name, first.contacts[i].parameters[k].name);
                EXPECT_EQ(second.contacts[i].parameters[k].values, first.contacts[i].parameters[k].values);
            }
        }
        EXPECT_EQ(second.output.logged_components, first.output.logged_components);
    }
}

// A nozzle placed by its target: 20 mm from a point on a surface facing +z, jet at 60 deg to it,
// leaning towards +y (azimuth 90 deg); its flow as a mass. Position, direction and rate follow, and
// the resolved scene reads back the same.
TEST(SceneParser, NozzlePlacedByItsTargetAndFedByMass) {
    const char* text = R"(
process: {duration: 1 s, gravity: [0, 0, -9.81]}
shot: {count: 0, diameter: 0.58 mm, density: 7.8 g/cm3}
components:
  - {name: plate, role: part, mesh: tetrahedron.stl}
sources:
  - name: nozzle
    target: [1 mm, 2 mm, 3 mm]
    distance: 20 mm
    angle_of_attack: 60 deg
    azimuth: 90 deg
    speed: 100 m/s
    mass_flow: 5.5 kg/min
    diameter: 6 mm
)";
    const SceneDescription s = parse_scene_text(text, virtual_path);
    ASSERT_EQ(s.sources.size(), 1u);
    const SourceDesc& n = s.sources[0];
    // Into the surface at 60 deg (sin 60 of -z), leaning along +y (cos 60).
    EXPECT_NEAR(n.direction.x(), 0.0, 1e-15);
    EXPECT_NEAR(n.direction.y(), 0.5, 1e-15);
    EXPECT_NEAR(n.direction.z(), -std::sqrt(3.0) / 2.0, 1e-15);
    const Vec3 target(1e-3, 2e-3, 3e-3);
    EXPECT_NEAR((n.position_m + 0.020 * n.direction - target).norm(), 0.0, 1e-17);
    // 5.5 kg/min of 0.58 mm, 7800 kg/m3 shot: 5.5 / 60 / (7800 pi 0.00058^3 / 6) = 115,036 per s.
    const double shot_mass = 7800.0 * pi * std::pow(0.58e-3, 3) / 6.0;
    EXPECT_NEAR(n.rate_per_s, 5.5 / 60.0 / shot_mass, 1e-9 * n.rate_per_s);
    EXPECT_NEAR(n.rate_per_s, 115036.1, 0.1);
    EXPECT_DOUBLE_EQ(n.exit_radius_m, 3e-3);
    EXPECT_DOUBLE_EQ(n.speed_spread, 0.05);  // the default: +-5 %
    const std::string resolved = resolved_scene_yaml(s);
    const SceneDescription again = parse_scene_text(resolved, "/nonexistent/dir/resolved.yaml");
    EXPECT_EQ(resolved_scene_yaml(again), resolved);
    EXPECT_EQ(again.sources[0].rate_per_s, n.rate_per_s);
    EXPECT_NEAR((again.sources[0].direction - n.direction).norm(), 0.0, 1e-15);
    EXPECT_NEAR((again.sources[0].position_m - n.position_m).norm(), 0.0, 1e-18);
    // Normal incidence by default; the normal defaults to the opposite of gravity.
    const SceneDescription straight = parse_scene_text(text, virtual_path, {"sources[nozzle].angle_of_attack=90 deg"});
    EXPECT_NEAR((straight.sources[0].direction - Vec3(0, 0, -1)).norm(), 0.0, 1e-15);
}

TEST(SceneParser, ShippedScenesParseAndReadBackTheSame) {
    int scenes = 0;
    for (const auto& entry : std::filesystem::directory_iterator(std::string(PEENSIM_SOURCE_DIR) + "/scenes")) {
        if (entry.path().extension() != ".yaml") continue;
        ++scenes;
        const SceneDescription s = parse_scene_file(entry.path().string());
        const std::string resolved = resolved_scene_yaml(s);
        EXPECT_EQ(resolved_scene_yaml(parse_scene_text(resolved, entry.path().string())), resolved) << entry.path();
    }
    EXPECT_GT(scenes, 0);
}

TEST(SceneParser, ResolvedSceneIsSiWithUnitComments) {
    const std::string resolved = resolved_scene_yaml(parse_scene_text(full_scene, virtual_path));
    EXPECT_NE(resolved.find("  diameter: 0.002  # m\n"), std::string::npos) << resolved;
    EXPECT_NE(resolved.find("      frequency: 20000  # Hz\n"), std::string::npos) << resolved;
    EXPECT_NE(resolved.find("      speed: 3.141592653589793  # rad/s\n"), std::string::npos) << resolved;
    EXPECT_NE(resolved.find("    mesh: " + tetrahedron_path() + "  # fnv1a64 "), std::string::npos) << resolved;  // its bytes' digest
    EXPECT_NE(resolved.find("  checkpoint_interval: 120  # s\n"), std::string::npos) << resolved;
}

TEST(SceneParser, HashFollowsContentNotSpelling) {
    const SceneDescription a = parse_scene_text(minimal_scene, virtual_path);
    const SceneDescription b = parse_scene_text(minimal_scene, virtual_path, {"shot.diameter=1 mm"});
    const SceneDescription c = parse_scene_text(minimal_scene, virtual_path, {"process.seed=2"});
    EXPECT_EQ(scene_hash(a), scene_hash(b));  // 0.001 written as "1 mm"
    EXPECT_NE(scene_hash(a), scene_hash(c));
}

// A mesh is part of what a run simulates by its bytes, not by its path: re-exported in place it is
// another scene (a resume or a sweep's finished run must not take it for the old one), copied
// elsewhere byte for byte it is the same one.
TEST(SceneParser, HashFollowsTheMeshFilesBytesNotTheirPaths) {
    namespace fs = std::filesystem;
    const peensim::testing::TempDir dir;
    fs::copy_file(tetrahedron_path(), dir.path / "part.stl");
    fs::create_directory(dir.path / "copy");
    fs::copy_file(tetrahedron_path(), dir.path / "copy" / "part.stl");
    const auto hash_with_part = [&](const fs::path& part) {
        return scene_hash(parse_scene_text(minimal_scene, virtual_path, {"components[rod].mesh=" + part.string()}));
    };
    const std::uint64_t original = hash_with_part(dir.path / "part.stl");
    EXPECT_EQ(hash_with_part(dir.path / "copy" / "part.stl"), original);
    // The same size, one byte of a vertex changed (the part moved, as a re-export would move it).
    std::string bytes;
    {
        std::ifstream in(dir.path / "part.stl", std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    ASSERT_GT(bytes.size(), 100u);
    const std::size_t digit = bytes.find_first_of("123456789", bytes.find("vertex"));
    ASSERT_NE(digit, std::string::npos);
    bytes[digit] = bytes[digit] == '9' ? '8' : static_cast<char>(bytes[digit] + 1);
    std::ofstream(dir.path / "part.stl", std::ios::binary | std::ios::trunc) << bytes;
    fs::last_write_time(dir.path / "part.stl", fs::last_write_time(dir.path / "part.stl") + std::chrono::seconds(1));
    EXPECT_NE(hash_with_part(dir.path / "part.stl"), original);
    EXPECT_EQ(hash_with_part(dir.path / "copy" / "part.stl"), original);
}

// A refusal of another scene says what differs: the first simulated setting, in the run's and the
// new scene's own words, or the mesh written since the run began.
TEST(SceneParser, TheDifferenceFromARunsSceneIsNamed) {
    namespace fs = std::filesystem;
    const peensim::testing::TempDir dir;
    fs::copy_file(tetrahedron_path(), dir.path / "part.stl");
    const std::string part = "components[rod].mesh=" + (dir.path / "part.stl").string();
    const fs::path resolved = dir.path / "scene.resolved.yaml";
    std::ofstream(resolved) << resolved_scene_yaml(parse_scene_text(minimal_scene, virtual_path, {part}));
    EXPECT_EQ(scene_difference(resolved.string(), parse_scene_text(minimal_scene, virtual_path, {part, "shot.diameter=1.5 mm"})),
              "shot: the run had `diameter: 0.001  # m`, now `diameter: 0.0015  # m`");
    EXPECT_EQ(scene_difference(resolved.string(),
                               parse_scene_text(minimal_scene, virtual_path, {part, "components[box].translation=[0, 0, 1 mm]"})),
              "components, box: the run had `translation: [0, 0, 0]  # m`, now `translation: [0, 0, 0.001]  # m`");
    // Another mesh file, of other bytes: said in words, with the file the scene names now.
    std::ofstream(dir.path / "other.stl") << peensim::testing::read_file(tetrahedron_path()) << "\n";
    EXPECT_EQ(scene_difference(resolved.string(), parse_scene_text(minimal_scene, virtual_path,
                                                                   {"components[rod].mesh=" + (dir.path / "other.stl").string()})),
              "components, rod: the mesh file's bytes differ from the run's (now `mesh: " + (dir.path / "other.stl").string() + "`)");
    // A contact pair's setting is named by its pair; a block added, as added.
    const std::string regions =
        scene_difference(resolved.string(),
                         parse_scene_text(minimal_scene, virtual_path,
                                          {part, "components[rod].regions=[{name: top, facing: {direction: [0, 0, 1], within: 30 deg}}]"}));
    EXPECT_EQ(regions.rfind("components, rod: now also `regions:; - {name: top, facing: {direction: [0, 0, 1], within: ", 0), 0u)
        << regions;
    EXPECT_NE(regions.find("`, which the run had not"), std::string::npos) << regions;
    // One block in place of another: both said (a static part made to turn).
    const std::string turning = scene_difference(
        resolved.string(),
        parse_scene_text(
            minimal_scene, virtual_path,
            {part, "components[rod].motion={type: rotating, axis_point: [0, 0, 0], axis_direction: [0, 0, 1], speed: 30 rpm}"}));
    EXPECT_EQ(turning.rfind("components, rod: the run had `motion: static`, now `motion:; type: rotating; axis_point: [0, 0, 0]; ...`", 0),
              0u)
        << turning;
    // The same settings, the part's mesh rewritten in place (its time set back: the bytes decide),
    // and the sonotrode's copied again with the same bytes: only the part is named.
    const auto written = fs::last_write_time(dir.path / "part.stl");
    std::ofstream(dir.path / "part.stl", std::ios::app) << "\n";
    fs::last_write_time(dir.path / "part.stl", written - std::chrono::hours(24));
    EXPECT_EQ(scene_difference(resolved.string(), parse_scene_text(minimal_scene, virtual_path, {part})),
              "the same settings, but the bytes of a mesh file differ from the run's: " + (dir.path / "part.stl").string());
    EXPECT_EQ(scene_difference((dir.path / "none.yaml").string(), parse_scene_text(minimal_scene, virtual_path, {part})), "");
}

TEST(SceneParser, ParsesAFileFromDisk) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / "peensim_scene_parser_test";
    fs::create_directories(dir / "meshes");
    fs::copy_file(tetrahedron_path(), dir / "meshes" / "t.stl", fs::copy_options::overwrite_existing);
    {
        std::ofstream out(dir / "scene.yaml");
        out << "process: {duration: 1 s}\nshot: {count: 1, diameter: 1 mm, density: 7800}\ncomponents:\n"
               "  - {name: s, role: sonotrode, mesh: meshes/t.stl, vibration: {amplitude: 0, frequency: 0}}\n"
               "  - {name: c, role: chamber, mesh: meshes/t.stl}\n";
    }
    const SceneDescription s = parse_scene_file((dir / "scene.yaml").string());
    EXPECT_EQ(s.components[0].mesh_path, (dir / "meshes" / "t.stl").string());
    EXPECT_EQ(s.components[0].vibration->amplitude_m, 0.0);
    EXPECT_TRUE(s.output.logged_components.empty());
    try {
        parse_scene_file((dir / "missing.yaml").string());
        ADD_FAILURE() << "a missing scene file was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("missing.yaml"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("cannot read the scene file"), std::string::npos);
    }
    fs::remove_all(dir);
}

TEST(SceneParser, DuplicateKeysAreErrors) {
    const std::string msg = error_of("process: {duration: 1}\nprocess: {duration: 2}\n");
    EXPECT_NE(msg.find("inline.yaml:2:1: process: key 'process' appears more than once"), std::string::npos) << msg;
}

TEST(SceneParser, EmptyOrNonMapSceneIsAnError) {
    EXPECT_NE(error_of("").find("the scene is empty"), std::string::npos);
    EXPECT_NE(error_of("- a\n- b\n").find("expected a map with keys name, process"), std::string::npos);
}

TEST(SceneParser, ZeroAmplitudeAllowsZeroFrequencyOnly) {
    const std::string text = std::string(minimal_scene);
    EXPECT_NO_THROW(parse_scene_text(text, virtual_path, {"components[sono].vibration={amplitude: 0, frequency: 0}"}));
    EXPECT_NE(error_of(text, {"components[sono].vibration={amplitude: 1 um, frequency: 0}"})
                  .find("expected a frequency > 0 Hz when the amplitude is > 0"),
              std::string::npos);
}

// A part with one region of every kind (line numbers below count from the opening newline).
const char* const regions_scene = R"(
process: {duration: 0.5}
shot: {count: 3, diameter: 0.001, density: 7800}
components:
  - {name: sono, role: sonotrode, mesh: tetrahedron.stl, vibration: {amplitude: 30 um, frequency: 20 kHz}}
  - {name: box, role: chamber, mesh: tetrahedron.stl}
  - name: gear
    role: part
    mesh: tetrahedron.stl
    regions:
      - {name: tooth-0, sector: {axis_point: [0, 0, 0], axis_direction: [0, 2, 0], from: -9 deg, to: 9 deg, reference: [0, 0, 1]}}
      - {name: teeth, sectors: {axis_direction: [0, 1, 0], count: 20, width: 18 deg, offset: 0 deg, reference: [0, 0, 1], name_prefix: tooth-x}}
      - {name: left-face, box: {min: [-1, -6 mm, -1], max: [1, -4.9 mm, 1]}}
      - {name: upper, half_space: {point: [0, 0, 0], normal: [0, 0, 3]}}
      - {name: solid-A, group: "A"}
      - {name: rim, sectors: {axis_direction: [0, 1, 0], count: 2, width: 180 deg, reference: [1, 0, 0]}}
      - {name: end-rim, facing: {direction: [0, 2, 0], within: 30 deg}, distance_to_axis: {axis_direction: [0, 1, 0], min: 15 mm}}
      - {name: hole, distance_to_point: {point: [0, 5 mm, 0], max: 2 mm}, exclude: true}
)";

TEST(SceneParser, RegionsAreReadInSi) {
    const SceneDescription s = parse_scene_text(regions_scene, virtual_path);
    const std::vector<RegionDesc>& r = s.components[2].regions;
    ASSERT_EQ(r.size(), 8u);
    ASSERT_TRUE(r[0].sector);
    EXPECT_EQ(r[0].sector->frame.axis_direction, Vec3(0, 1, 0));
    EXPECT_DOUBLE_EQ(r[0].sector->from_rad, -9 * pi / 180);
    EXPECT_DOUBLE_EQ(r[0].sector->to_rad, 9 * pi / 180);
    EXPECT_EQ(r[0].where.line, 11);
    EXPECT_FALSE(r[0].exclude);
    ASSERT_TRUE(r[1].sectors);
    EXPECT_EQ(r[1].sectors->count, 20);
    EXPECT_DOUBLE_EQ(r[1].sectors->width_rad, 18 * pi / 180);
    EXPECT_EQ(region_names(r[1]).back(), "tooth-x19");
    ASSERT_TRUE(r[2].box);
    EXPECT_EQ(r[2].box->min_m, Vec3(-1, -0.006, -1));
    ASSERT_TRUE(r[3].half_space);
    EXPECT_EQ(r[3].half_space->normal, Vec3(0, 0, 1));
    EXPECT_EQ(r[4].group, "A");
    EXPECT_EQ(r[5].sectors->name_prefix, "rim-");  // the default prefix is the entry's name and a dash
    EXPECT_EQ(region_names(r[5]), (std::vector<std::string>{"rim-0", "rim-1"}));
    // Several conditions in one entry, a distance with no upper bound, an excluded region.
    ASSERT_TRUE(r[6].facing && r[6].distance_to_axis && !r[6].sector);
    EXPECT_EQ(r[6].facing->direction, Vec3(0, 1, 0));
    EXPECT_DOUBLE_EQ(r[6].facing->within_rad, 30 * pi / 180);
    EXPECT_DOUBLE_EQ(r[6].distance_to_axis->min_m, 0.015);
    EXPECT_TRUE(std::isinf(r[6].distance_to_axis->max_m));
    EXPECT_TRUE(r[7].exclude);
    EXPECT_EQ(r[7].distance_to_point->point_m, Vec3(0, 0.005, 0));
    EXPECT_DOUBLE_EQ(r[7].distance_to_point->max_m, 0.002);
    EXPECT_EQ(r[7].distance_to_point->min_m, 0.0);
}

TEST(SceneParser, AWholeNumberMayBeWrittenWithAnExponent) {
    std::string text = regions_scene;
    const std::string twenty = "count: 20, width: 18 deg";
    text.replace(text.find(twenty), twenty.size(), "count: 2e1, width: 18 deg");
    EXPECT_EQ(parse_scene_text(text, virtual_path).components[2].regions[1].sectors->count, 20);
}

TEST(SceneParser, RegionsReadBackTheSame) {
    const SceneDescription first = parse_scene_text(regions_scene, virtual_path);
    const std::string resolved = resolved_scene_yaml(first);
    EXPECT_NE(resolved.find("    regions:\n      - {name: tooth-0, sector: {"), std::string::npos) << resolved;
    EXPECT_NE(resolved.find("distance_to_point: {point: [0, 0.005, 0], min: 0, max: 0.002}, exclude: true}"), std::string::npos)
        << resolved;
    const SceneDescription second = parse_scene_text(resolved, "/nonexistent/dir/resolved.yaml");
    EXPECT_EQ(resolved_scene_yaml(second), resolved);
    ASSERT_EQ(second.components[2].regions.size(), 8u);
    for (std::size_t i = 0; i < 8; ++i) {
        const RegionDesc& a = first.components[2].regions[i];
        const RegionDesc& b = second.components[2].regions[i];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.sector.has_value(), b.sector.has_value());
        if (a.sector) {
            EXPECT_EQ(a.sector->from_rad, b.sector->from_rad);
        }
        if (a.sectors) {
            EXPECT_EQ(a.sectors->width_rad, b.sectors->width_rad);
            EXPECT_EQ(a.sectors->frame.reference, b.sectors->frame.reference);
            EXPECT_EQ(a.sectors->name_prefix, b.sectors->name_prefix);
        }
        if (a.box) {
            EXPECT_EQ(a.box->max_m, b.box->max_m);
        }
        EXPECT_EQ(a.group, b.group);
        EXPECT_EQ(a.facing.has_value(), b.facing.has_value());
        if (a.distance_to_axis) {
            EXPECT_EQ(a.distance_to_axis->max_m, b.distance_to_axis->max_m);
        }
        EXPECT_EQ(a.exclude, b.exclude);
    }
}

// Replaces the region entries of regions_scene (line 11 on) with `entry`, one region on line 11.
std::string scene_with_region(const std::string& entry) {
    const std::string text = regions_scene;
    return text.substr(0, text.find("      - {name: tooth-0")) + "      - " + entry + "\n";
}

TEST(SceneParser, BadRegionsNameLineAndField) {
    struct Bad {
        std::string entry;
        std::string field;
        std::string problem;
    };
    const Bad bad[] = {
        {"{name: a, box: {min: [0, 0, 0], max: [1, 1, 1], mid: [0, 0, 0]}}", "components[2].regions[0].box.mid", "unknown key 'mid'"},
        {"{name: a, box: {min: [0, 0, 0]}}", "components[2].regions[0].box.max", "missing required key 'max'"},
        {"{name: a, box: {min: [0, 0, 0], max: [1, -1, 1]}}", "components[2].regions[0].box.max", "expected a corner >= min"},
        {"{name: a, half_space: {normal: [0, 0, 0]}}", "components[2].regions[0].half_space.normal",
         "expected a direction, got the zero vector"},
        {"{name: a, sector: {axis_direction: [0, 0, 0], from: 0, to: 1, reference: [1, 0, 0]}}",
         "components[2].regions[0].sector.axis_direction", "expected a direction, got the zero vector"},
        {"{name: a, sector: {axis_direction: [0, 1, 0], from: 10 deg, to: 10 deg, reference: [1, 0, 0]}}",
         "components[2].regions[0].sector.to", "expected an angle greater than `from`"},
        {"{name: a, sector: {axis_direction: [0, 1, 0], from: 0, to: 1, reference: [0, 2, 0]}}",
         "components[2].regions[0].sector.reference", "not along the axis"},
        {"{name: a, sectors: {axis_direction: [0, 1, 0], count: 0, width: 1 deg, reference: [1, 0, 0]}}",
         "components[2].regions[0].sectors.count", "expected a whole number in [1, 3600], got '0'"},
        {"{name: a, sectors: {axis_direction: [0, 1, 0], count: 4294967296, width: 1 deg, reference: [1, 0, 0]}}",
         "components[2].regions[0].sectors.count", "expected a whole number in [1, 3600], got '4294967296'"},
        // A whole number may be written with an exponent, but is range-checked before it is converted.
        {"{name: a, sectors: {axis_direction: [0, 1, 0], count: 4e3, width: 1 deg, reference: [1, 0, 0]}}",
         "components[2].regions[0].sectors.count", "expected a whole number in [1, 3600], got '4e3'"},
        {"{name: a, sectors: {axis_direction: [0, 1, 0], count: 1e400, width: 1 deg, reference: [1, 0, 0]}}",
         "components[2].regions[0].sectors.count", "expected a whole number in [1, 3600], got '1e400'"},
        {"{name: a, sectors: {axis_direction: [0, 1, 0], count: 2.5e0, width: 1 deg, reference: [1, 0, 0]}}",
         "components[2].regions[0].sectors.count", "expected a whole number in [1, 3600], got '2.5e0'"},
        {"{name: a, sectors: {axis_direction: [0, 1, 0], count: 2, width: 361 deg, reference: [1, 0, 0]}}",
         "components[2].regions[0].sectors.width", "at most 360 deg"},
        {"{name: a}", "components[2].regions[0]", "expected at least one of sector, sectors, box, half_space, distance_to_axis"},
        {"{name: a, sector: {axis_direction: [0, 1, 0], from: 0, to: 1, reference: [1, 0, 0]}, sectors: {axis_direction: [0, 1, 0], count: "
         "2, "
         "width: 1 deg, reference: [1, 0, 0]}}",
         "components[2].regions[0].sectors", "expected `sector` or `sectors`, not both"},
        {"{name: a, facing: {direction: [0, 0, 0], within: 10 deg}}", "components[2].regions[0].facing.direction",
         "expected a direction, got the zero vector"},
        {"{name: a, facing: {direction: [0, 0, 1], within: 181 deg}}", "components[2].regions[0].facing.within",
         "expected at most 180 deg"},
        {"{name: a, facing: {direction: [0, 0, 1], within: 0 deg}}", "components[2].regions[0].facing.within", "expected an angle > 0"},
        {"{name: a, distance_to_axis: {axis_direction: [0, 0, 1], min: 2 mm, max: 1 mm}}", "components[2].regions[0].distance_to_axis.max",
         "expected a distance greater than `min`"},
        {"{name: a, distance_to_axis: {axis_direction: [0, 0, 1]}}", "components[2].regions[0].distance_to_axis",
         "expected `max`, or a `min` above 0"},
        {"{name: a, distance_to_point: {point: [0, 0, 0], min: -1 mm}}", "components[2].regions[0].distance_to_point.min",
         "expected a length >= 0"},
        {"{name: a, group: A, exclude: yes}", "components[2].regions[0].exclude", "expected one of true, false"},
        {"{name: a b, group: A}", "components[2].regions[0].name", "invalid name 'a b'"},
    };
    for (const Bad& b : bad) {
        try {
            parse_scene_text(scene_with_region(b.entry), virtual_path);
            ADD_FAILURE() << b.entry << " was accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(e.where().file, virtual_path) << e.what();
            EXPECT_EQ(e.where().line, 11) << e.what();
            EXPECT_EQ(e.field(), b.field) << e.what();
            EXPECT_NE(e.problem().find(b.problem), std::string::npos) << e.what();
        }
    }
}

TEST(SceneParser, DuplicateRegionNamesAreRefused) {
    std::string text = scene_with_region("{name: tooth-3, group: A}");
    text +=
        "      - {name: teeth, sectors: {axis_direction: [0, 1, 0], count: 20, width: 18 deg, reference: [0, 0, 1], "
        "name_prefix: tooth-}}\n";
    try {
        parse_scene_text(text, virtual_path);
        ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where().line, 12) << e.what();
        EXPECT_EQ(e.field(), "components[2].regions[1].name");
        EXPECT_NE(e.problem().find("duplicate region name 'tooth-3'"), std::string::npos) << e.what();
    }
}

TEST(SceneParser, RenderBlockReadsInSIAndIsLeftOutOfTheSceneHash) {
    const SceneDescription plain = parse_scene_text(minimal_scene, virtual_path);
    EXPECT_FALSE(plain.render.has_value());
    // An empty block takes every default.
    const SceneDescription defaults = parse_scene_text(std::string(minimal_scene) + "render: {}\n", virtual_path);
    ASSERT_TRUE(defaults.render.has_value());
    EXPECT_EQ(defaults.render->width_px, 1280);
    EXPECT_EQ(defaults.render->height_px, 720);
    EXPECT_EQ(defaults.render->fps, 30);
    EXPECT_EQ(defaults.render->slow_motion_s, 0.02);
    EXPECT_EQ(defaults.render->duration_s, 0.2);
    EXPECT_FALSE(defaults.render->camera_position_m.has_value());
    EXPECT_DOUBLE_EQ(defaults.render->fov_rad, 40.0 * pi / 180.0);
    EXPECT_TRUE(defaults.render->video);

    const SceneDescription s =
        parse_scene_text(std::string(minimal_scene) +
                             "render: {width: 640, height: 480, fps: 25, slow_motion: 5 ms, start: 0.1 s, duration: 50 ms,\n"
                             "         camera: {position: [0, -100 mm, 50 mm], look_at: [0, 0, 20 mm], up: [0, 0, 2], fov: 30 deg},\n"
                             "         speed_scale: 3 m/s, video: none}\n",
                         virtual_path);
    ASSERT_TRUE(s.render.has_value());
    const RenderDesc& r = *s.render;
    EXPECT_EQ(r.width_px, 640);
    EXPECT_EQ(r.fps, 25);
    EXPECT_EQ(r.slow_motion_s, 0.005);
    EXPECT_EQ(r.start_s, 0.1);
    EXPECT_EQ(r.duration_s, 0.05);
    EXPECT_EQ(*r.camera_position_m, Vec3(0, -0.1, 0.05));
    EXPECT_EQ(*r.camera_look_at_m, Vec3(0, 0, 0.02));
    EXPECT_EQ(r.camera_up, Vec3(0, 0, 1));
    EXPECT_DOUBLE_EQ(r.fov_rad, pi / 6);
    EXPECT_EQ(r.speed_scale_m_per_s, 3.0);
    EXPECT_FALSE(r.video);
    // The resolved scene keeps the block (a resumed run reads it back the same) ...
    EXPECT_NE(resolved_scene_yaml(s).find("render:\n  width: 640"), std::string::npos);
    // ... but rendering does not change what is simulated: the hash ignores it.
    EXPECT_EQ(scene_hash(s), scene_hash(plain));

    EXPECT_NE(error_of(minimal_scene, {"render.fps=0"}).find("render.fps"), std::string::npos);
    EXPECT_NE(error_of(minimal_scene, {"render.camera.fov=180 deg"}).find("render.camera.fov"), std::string::npos);
    EXPECT_NE(error_of(minimal_scene, {"render.camera.position=[0,0,1]", "render.camera.look_at=[0,0,1]"})
                  .find("expected a point other than the camera position"),
              std::string::npos);
    EXPECT_NE(error_of(minimal_scene, {"render.video=avi"}).find("render.video"), std::string::npos);
}

// A scene's parse grows with its size, not its square: a look-up of a key no longer merges the
// whole document's nodes into a placeholder (yaml-cpp's assignment), which made a scene with 3000
// materials take ~10 s to read (and every sweep variant of the gear 5-10 ms).
TEST(SceneParser, ALargeSceneIsReadInLinearTime) {
    std::string text = full_scene;
    std::string many;
    for (int k = 0; k < 3000; ++k) many += "  m" + std::to_string(k) + ": {density: 7.8 g/cm3}\n";
    text.replace(text.find("materials:\n") + 11, 0, many);
    const auto t0 = std::chrono::steady_clock::now();
    const SceneDescription d = parse_scene_text(text, virtual_path);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(d.materials.size(), 3003u);
    EXPECT_LT(seconds, 2.0);  // ~0.05 s here; ~10 s before
}

}  // namespace
}  // namespace peensim
