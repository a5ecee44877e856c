// Defaults and ranges have one source, the schema (src/scene/schema.cpp): a scene that leaves a key
// out parses to the schema's default, and a value just outside the schema's range is refused naming
// the key. Both tests iterate the schema, so a key added later is checked too (or fails here until
// it is given an accessor).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "common/input_error.h"
#include "common/units.h"
#include "contact/law_registry.h"
#include "scene/scene_parser.h"
#include "scene/schema.h"
#include "scene/schema_defaults.h"

namespace peensim {
namespace {

namespace fs = std::filesystem;

// Every block under which a key has a default, without any of those keys (only required ones and
// what selects a block's kind). The parser only checks that a mesh file exists, so one empty file
// stands for every mesh. SIZE is one `diameter`, or a mix for the keys under shot.sizes.
constexpr const char* kBareScene = R"(process: {duration: 0.1}
shot: {count: 10, SIZE, density: 7800}
air:
  rebound_scatter: {spread: 0.1}
materials:
  steel: {density: 7800, yield_stress: 1e9}
  glass: {density: 2500}
contacts:
  shot-steel: {law: impact-history, restitution_by_hits: [0.5]}
  shot-glass: {law: linear-spring-dashpot}
  shot-shot: {law: hertz-mindlin}
components:
  - name: horn
    role: sonotrode
    mesh: m.stl
    vibration: {amplitude: 2e-5, frequency: 2e4}
  - {name: box, role: chamber, mesh: m.stl, material: glass}
  - name: gear
    role: part
    mesh: m.stl
    material: steel
    motion: {type: rotating, axis_point: [0, 0, 0], axis_direction: [0, 0, 1], speed: 1}
    regions:
      - {name: sector, sector: {axis_direction: [0, 0, 1], reference: [1, 0, 0], from: 0, to: 1}}
      - {name: sectors, sectors: {axis_direction: [0, 0, 1], reference: [1, 0, 0], count: 4, width: 0.5}}
      - {name: box, box: {min: [0, 0, 0], max: [1, 1, 1]}}
      - {name: half_space, half_space: {normal: [0, 0, 1]}}
      - {name: distance_to_axis, distance_to_axis: {axis_direction: [0, 0, 1], max: 1}}
      - {name: distance_to_point, distance_to_point: {point: [0, 0, 0], max: 1}}
      - {name: facing, facing: {direction: [0, 0, 1], within: 1}}
  - name: strip
    role: almen
    mesh: m.stl
    almen: {calibration: {saturation_arc_height: 2e-4, time_constant: 1, dent_size: 3e-4, covering_rate: 1}}
  - {name: strip2, role: almen, mesh: m.stl}
  - {name: cad, role: fixture, mesh: m.step}
sources:
  - {name: jet, target: [0, 0, 0], distance: 0.1, speed: 50, rate: 100}
  - {name: jet2, position: [0, 0, 1], direction: [0, 0, -1], speed: 50, mass_flow: 0.1}
sinks:
  - {name: drain, region: mesh, mesh: m.stl}
output: {}
render: {}
)";

// The bare scene written to its own directory (beside its mesh file), parsed with `overrides`.
SceneDescription parse_bare(const std::vector<std::string>& overrides = {}, bool mix = false) {
    static const fs::path dir = [] {
        const fs::path d = fs::temp_directory_path() / "peensim_scene_defaults_agree_test";
        fs::create_directories(d);
        std::ofstream(d / "m.stl") << "solid empty\nendsolid empty\n";
        std::ofstream(d / "m.step") << "ISO-10303-21;\nEND-ISO-10303-21;\n";  // (a STEP file: `tessellation`)
        return d;
    }();
    std::string text = kBareScene;
    text.replace(text.find("SIZE"), 4, mix ? "sizes: [{diameter: 1e-3, fraction: 1}]" : "diameter: 1e-3");
    return parse_scene_text(text, (dir / "bare.yaml").string(), overrides);
}

using Value = std::variant<double, long long, Vec3, std::string>;
using Accessor = std::function<Value(const SceneDescription&)>;

const ComponentDesc& component(const SceneDescription& s, const std::string& name) {
    for (const ComponentDesc& k : s.components)
        if (k.name == name) return k;
    throw std::out_of_range("no component " + name);
}

const RegionDesc& region(const SceneDescription& s, const std::string& name) {
    for (const RegionDesc& r : component(s, "gear").regions)
        if (r.name == name) return r;
    throw std::out_of_range("no region " + name);
}

const ContactPairDesc& pair(const SceneDescription& s, const std::string& key) {
    for (const ContactPairDesc& p : s.contacts)
        if (p.key == key) return p;
    throw std::out_of_range("no contact pair " + key);
}

// The pair of the bare scene that uses each law (its parameters' defaults are read there).
const std::map<std::string, std::string>& pair_of_law() {
    static const std::map<std::string, std::string> m{
        {"impulse", "default"}, {"impact-history", "shot-steel"}, {"hertz-mindlin", "shot-shot"}, {"linear-spring-dashpot", "shot-glass"}};
    return m;
}

// The mesh-unit word of a scale (the description keeps metres per unit).
std::string mesh_unit_word(double metres_per_unit) {
    for (std::string_view w : split_choices(find_schema_entry("components[].mesh_unit")->choices))
        if (parse_quantity("1 " + std::string(w), Dimension::length) == metres_per_unit) return std::string(w);
    return "?";
}

// Where the description keeps each defaulted key's value, as the schema would write it.
const std::map<std::string, Accessor>& accessors() {
    using S = SceneDescription;
    static const std::map<std::string, Accessor> m{
        {"process.gravity", [](const S& s) -> Value { return s.process.gravity_m_per_s2; }},
        {"process.seed", [](const S& s) -> Value { return static_cast<long long>(s.process.seed); }},
        {"accuracy.travel_fraction", [](const S& s) -> Value { return s.accuracy.travel_fraction; }},
        {"accuracy.impact_speed", [](const S& s) -> Value { return s.accuracy.impact_speed_m_per_s; }},
        {"accuracy.scheme", [](const S& s) -> Value { return std::string(scheme_name(s.accuracy.scheme)); }},
        {"accuracy.soft_steps_per_contact", [](const S& s) -> Value { return s.accuracy.soft_steps_per_contact; }},
        {"shot.fractions_by", [](const S& s) -> Value { return std::string(s.shot.fractions_by_mass ? "mass" : "count"); }},
        {"air.drag", [](const S& s) -> Value { return std::string(s.air.drag ? "sphere" : "none"); }},
        {"air.density", [](const S& s) -> Value { return s.air.density_kg_per_m3; }},
        {"air.viscosity", [](const S& s) -> Value { return s.air.viscosity_pa_s; }},
        {"air.rebound_scatter.min_reynolds", [](const S& s) -> Value { return s.air.rebound_scatter.value().min_reynolds; }},
        {"air.rebound_scatter.min_speed", [](const S& s) -> Value { return s.air.rebound_scatter.value().min_speed_m_per_s; }},
        {"contacts.*.law", [](const S& s) -> Value { return pair(s, "default").law; }},
        {"components[].mesh_unit", [](const S& s) -> Value { return mesh_unit_word(component(s, "horn").mesh_unit_m); }},
        {"components[].translation", [](const S& s) -> Value { return component(s, "horn").translation_m; }},
        {"components[].tessellation.chordal", [](const S& s) -> Value { return component(s, "cad").tessellation.chordal_m; }},
        {"components[].tessellation.angular", [](const S& s) -> Value { return component(s, "cad").tessellation.angular_rad; }},
        {"components[].vibration.phase", [](const S& s) -> Value { return component(s, "horn").vibration.value().phase_rad; }},
        {"components[].almen.face_normal", [](const S& s) -> Value { return component(s, "strip").almen.value().face_normal; }},
        {"components[].almen.calibration.shape",
         [](const S& s) -> Value { return component(s, "strip").almen.value().calibration.value().shape; }},
        {"components[].regions[].sector.axis_point", [](const S& s) -> Value { return region(s, "sector").sector->frame.axis_point_m; }},
        {"components[].regions[].sectors.axis_point", [](const S& s) -> Value { return region(s, "sectors").sectors->frame.axis_point_m; }},
        {"components[].regions[].sectors.offset", [](const S& s) -> Value { return region(s, "sectors").sectors->offset_rad; }},
        {"components[].regions[].half_space.point", [](const S& s) -> Value { return region(s, "half_space").half_space->point_m; }},
        {"components[].regions[].distance_to_axis.axis_point",
         [](const S& s) -> Value { return region(s, "distance_to_axis").distance_to_axis->axis_point_m; }},
        {"components[].regions[].distance_to_axis.min",
         [](const S& s) -> Value { return region(s, "distance_to_axis").distance_to_axis->min_m; }},
        {"components[].regions[].distance_to_point.min",
         [](const S& s) -> Value { return region(s, "distance_to_point").distance_to_point->min_m; }},
        {"components[].regions[].exclude", [](const S& s) -> Value { return std::string(region(s, "box").exclude ? "true" : "false"); }},
        {"sources[].angle_of_attack", [](const S& s) -> Value { return s.sources.at(0).aim.value().angle_of_attack_rad; }},
        {"sources[].azimuth", [](const S& s) -> Value { return s.sources.at(0).aim.value().azimuth_rad; }},
        {"sources[].kind",
         [](const S& s) -> Value { return std::string(s.sources.at(0).kind == SourceKind::hopper ? "hopper" : "nozzle"); }},
        {"sources[].speed_spread", [](const S& s) -> Value { return s.sources.at(0).speed_spread; }},
        {"sources[].exit_radius", [](const S& s) -> Value { return s.sources.at(0).exit_radius_m; }},
        {"sources[].spread", [](const S& s) -> Value { return s.sources.at(0).spread_rad; }},
        {"sources[].start", [](const S& s) -> Value { return s.sources.at(0).start_s; }},
        {"sinks[].mesh_unit", [](const S& s) -> Value { return mesh_unit_word(s.sinks.at(0).mesh_unit_m); }},
        {"sinks[].translation", [](const S& s) -> Value { return s.sinks.at(0).translation_m; }},
        {"output.checkpoint_interval", [](const S& s) -> Value { return s.output.checkpoint_interval_s; }},
        {"output.coverage_steps", [](const S& s) -> Value { return static_cast<long long>(s.output.coverage_steps); }},
        {"render.width", [](const S& s) -> Value { return static_cast<long long>(s.render.value().width_px); }},
        {"render.height", [](const S& s) -> Value { return static_cast<long long>(s.render.value().height_px); }},
        {"render.fps", [](const S& s) -> Value { return static_cast<long long>(s.render.value().fps); }},
        {"render.slow_motion", [](const S& s) -> Value { return s.render.value().slow_motion_s; }},
        {"render.start", [](const S& s) -> Value { return s.render.value().start_s; }},
        {"render.duration", [](const S& s) -> Value { return s.render.value().duration_s; }},
        {"render.camera.up", [](const S& s) -> Value { return s.render.value().camera_up; }},
        {"render.camera.fov", [](const S& s) -> Value { return s.render.value().fov_rad; }},
        {"render.speed_scale", [](const S& s) -> Value { return s.render.value().speed_scale_m_per_s; }},
        {"render.video", [](const S& s) -> Value { return std::string(s.render.value().video ? "mp4" : "none"); }},
    };
    return m;
}

// The schema's default of an entry, as the description would hold it.
Value schema_default(const SchemaEntry& e) {
    switch (e.kind) {
        case ValueKind::quantity: return schema_default_quantity(e.path);
        case ValueKind::integer: return schema_default_integer(e.path);
        case ValueKind::vector3: return schema_default_vector(e.path);
        default: return schema_default_word(e.path);
    }
}

// All 17 digits: the values must agree exactly, not to a printed precision.
std::string exact(double v) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", v);
    return text;
}

std::string show(const Value& v) {
    if (const double* d = std::get_if<double>(&v)) return exact(*d);
    if (const long long* i = std::get_if<long long>(&v)) return std::to_string(*i);
    if (const Vec3* x = std::get_if<Vec3>(&v)) return "[" + exact(x->x()) + ", " + exact(x->y()) + ", " + exact(x->z()) + "]";
    return "'" + std::get<std::string>(v) + "'";
}

bool is_law_parameter(std::string_view path) { return path.rfind("contacts.*.", 0) == 0 && path != "contacts.*.law"; }

TEST(SceneDefaultsAgree, EveryDefaultOfTheSchemaIsWhatAParsedSceneHolds) {
    const SceneDescription bare = parse_bare();
    int checked = 0;
    for (const SchemaEntry& e : scene_schema()) {
        if (e.default_value.empty()) continue;
        // The contact laws' parameters: checked law by law below (one key, several laws).
        if (is_law_parameter(e.path)) continue;
        const auto it = accessors().find(std::string(e.path));
        ASSERT_NE(it, accessors().end()) << "schema entry '" << e.path << "' has a default (" << e.default_value
                                         << ") but no accessor in this test: add where the description keeps it";
        EXPECT_EQ(show(it->second(bare)), show(schema_default(e))) << e.path << " (schema default '" << e.default_value << "')";
        ++checked;
    }
    // No accessor for a key the schema has no default for (a stale entry after a schema change).
    for (const auto& [path, accessor] : accessors()) {
        const SchemaEntry* e = find_schema_entry(path);
        EXPECT_TRUE(e != nullptr && !e->default_value.empty()) << path << " is no schema entry with a default";
    }
    EXPECT_EQ(checked, static_cast<int>(accessors().size()));
}

TEST(SceneDefaultsAgree, EveryLawParameterDefaultIsTheSchemasAndWhatAParsedPairHolds) {
    const SceneDescription bare = parse_bare();
    int checked = 0;
    for (const contact::LawEntry& law : contact::law_catalogue()) {
        const auto at = pair_of_law().find(std::string(law.name));
        ASSERT_NE(at, pair_of_law().end()) << "law '" << law.name << "' has no pair in this test's bare scene: add one";
        const ContactPairDesc& p = pair(bare, at->second);
        ASSERT_EQ(p.law, law.name) << at->second;
        const bool shot_shot = at->second == "shot-shot";
        for (const contact::LawParameter& lp : shot_shot ? law.shot_shot_parameters : law.surface_parameters) {
            const std::string path = "contacts.*." + std::string(lp.name);
            const SchemaEntry* e = find_schema_entry(path);
            ASSERT_NE(e, nullptr) << path;
            // The schema holds one entry per key: every law declaring it must declare the same default.
            EXPECT_EQ(e->default_value, lp.default_value) << law.name << "." << lp.name;
            if (lp.default_value.empty()) continue;
            EXPECT_EQ(exact(p.value(lp.name)), exact(schema_default_quantity(path))) << law.name << "." << lp.name;
            ++checked;
        }
    }
    EXPECT_GT(checked, 5);
}

// The field path an override takes for a schema path: list items and names chosen in the bare scene.
std::string field_path_of(std::string_view schema_path) {
    static const std::map<std::string, std::string> item_of_list{{"shot.sizes", "0"}, {"sources", "jet"}, {"sinks", "drain"}};
    std::string path(schema_path);
    const auto replace = [&path](const std::string& from, const std::string& to) {
        if (const std::size_t at = path.find(from); at != std::string::npos) path.replace(at, from.size(), to);
    };
    if (path.rfind("components[].", 0) == 0) {
        const std::string rest = path.substr(13);
        const std::string block = rest.substr(0, rest.find_first_of(".["));
        const std::string owner = block == "vibration"                                                ? "horn"
                                  : block == "almen" && rest.find("calibration") != std::string::npos ? "strip"
                                  : block == "almen"                                                  ? "strip2"
                                  : block == "regions" || block == "motion"                           ? "gear"
                                  : block == "tessellation"                                           ? "cad"
                                                                                                      : "horn";
        replace("components[]", "components[" + owner + "]");
    }
    if (const std::size_t at = path.find("regions[]."); at != std::string::npos) {
        const std::string condition = path.substr(at + 10, path.find('.', at + 10) - (at + 10));
        replace("regions[]", "regions[" + condition + "]");
    }
    if (path.rfind("sources[].mass_flow", 0) == 0) replace("sources[]", "sources[jet2]");
    for (const auto& [list, item] : item_of_list) replace(list + "[]", list + "[" + item + "]");
    replace("materials.*", "materials.steel");
    if (is_law_parameter(schema_path)) {
        // The pair of the first law that declares it.
        std::string law_pair;
        for (const contact::LawEntry& law : contact::law_catalogue())
            for (const contact::LawParameter& p : law.surface_parameters)
                if (law_pair.empty() && "contacts.*." + std::string(p.name) == schema_path)
                    law_pair = pair_of_law().at(std::string(law.name));
        replace("contacts.*", "contacts." + law_pair);
    }
    return path;
}

// A value just outside a range, with its SI unit ("" if the range is unbounded).
std::string outside(const SchemaEntry& e) {
    const Range& r = e.range;
    const bool integer = e.kind == ValueKind::integer;
    double v = 0.0;
    if (std::isfinite(r.lo))
        v = r.lo_open ? r.lo : r.lo - (integer ? 1.0 : std::max(1e-3, std::abs(r.lo) * 1e-3));
    else if (std::isfinite(r.hi))
        v = r.hi_open ? r.hi : r.hi + (integer ? 1.0 : std::max(1e-3, std::abs(r.hi) * 1e-3));
    std::string text = exact(v);
    if (e.dimension != Dimension::dimensionless) text += " " + std::string(si_unit(e.dimension));
    return e.kind == ValueKind::quantity_list ? "[" + text + "]" : text;
}

// The partner a key needs before its range is read (the dose model's two constants go together).
const std::map<std::string, std::string>& partner_overrides() {
    static const std::map<std::string, std::string> m{
        {"components[].almen.saturation_arc_height", "components[strip2].almen.dose_constant=1"},
        {"components[].almen.dose_constant", "components[strip2].almen.saturation_arc_height=1e-4"},
    };
    return m;
}

TEST(SceneDefaultsAgree, AValueJustOutsideTheSchemasRangeIsRefusedNamingTheKey) {
    int checked = 0;
    for (const SchemaEntry& e : scene_schema()) {
        const bool numeric = e.kind == ValueKind::quantity || e.kind == ValueKind::integer || e.kind == ValueKind::quantity_list;
        if (!numeric || e.range.unbounded()) continue;
        const std::string field = field_path_of(e.path);
        std::vector<std::string> overrides{field + "=" + outside(e)};
        if (const auto p = partner_overrides().find(std::string(e.path)); p != partner_overrides().end()) overrides.push_back(p->second);
        const bool mix = std::string_view(e.path).rfind("shot.sizes[]", 0) == 0;
        try {
            (void)parse_bare(overrides, mix);
            ADD_FAILURE() << e.path << ": " << overrides.front() << " was accepted, outside " << e.range.text();
        } catch (const InputError& error) {
            // The field names the key (its last part; list items by index: "components[0]", a
            // table's value "restitution_by_hits[0]").
            const std::string key = std::string(e.path.substr(e.path.rfind('.') + 1));
            std::string named = error.field().substr(error.field().rfind('.') + 1);
            named = named.substr(0, named.find('['));
            EXPECT_EQ(named, key) << e.path << ": " << error.what();
            EXPECT_NE(error.problem().find("expected"), std::string::npos) << e.path << ": " << error.what();
            EXPECT_NE(error.problem().find(e.range.text()), std::string::npos) << e.path << ": " << error.what();
            EXPECT_EQ(error.where().file, "<--set>") << e.path << ": " << error.what();
        }
        ++checked;
    }
    EXPECT_GT(checked, 40);
}

TEST(SceneDefaultsAgree, ARunWithoutARenderBlockRecordsWithTheSchemasDefaults) {
    // `run --render` on a scene without a block: the same settings as an empty block.
    const RenderDesc d = default_render();
    const RenderDesc parsed = parse_bare().render.value();
    EXPECT_EQ(d.width_px, parsed.width_px);
    EXPECT_EQ(d.height_px, parsed.height_px);
    EXPECT_EQ(d.fps, parsed.fps);
    EXPECT_EQ(d.slow_motion_s, parsed.slow_motion_s);
    EXPECT_EQ(d.start_s, parsed.start_s);
    EXPECT_EQ(d.duration_s, parsed.duration_s);
    EXPECT_EQ(d.camera_up, parsed.camera_up);
    EXPECT_EQ(d.fov_rad, parsed.fov_rad);
    EXPECT_EQ(d.speed_scale_m_per_s, parsed.speed_scale_m_per_s);
    EXPECT_EQ(d.video, parsed.video);
    EXPECT_EQ(d.width_px, schema_default_integer("render.width"));
    EXPECT_EQ(d.fov_rad, schema_default_quantity("render.camera.fov"));
}

TEST(SceneDefaultsAgree, AskingForADefaultTheSchemaDoesNotHaveIsAProgrammingError) {
    EXPECT_THROW((void)schema_default_quantity("process.duration"), std::logic_error);  // required: no default
    EXPECT_THROW((void)schema_default_quantity("no.such.key"), std::logic_error);
    EXPECT_THROW((void)schema_default_integer("render.slow_motion"), std::logic_error);  // a quantity, not an integer
}

}  // namespace
}  // namespace peensim
