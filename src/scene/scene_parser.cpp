#include "scene/scene_parser.h"

#include <algorithm>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/units.h"
#include "scene/overrides.h"
#include "scene/scene_sections.h"
#include "scene/schema_validation.h"
#include "scene/shot_mix.h"
#include "scene/yaml_access.h"
#include "scene/yaml_load.h"

namespace peensim {
namespace {

// Shot start on a sonotrode (shot.count of them) or come from sources: an ultrasonic chamber needs
// its sonotrode and chamber, a scene fed by nozzles may have neither.
void check_shot_origin(const Cursor& root, const SceneDescription& d) {
    int sonotrodes = 0, chambers = 0;
    for (const ComponentDesc& k : d.components) {
        sonotrodes += k.role == ComponentRole::sonotrode;
        chambers += k.role == ComponentRole::chamber;
    }
    if (d.shot.count > 0 && sonotrodes == 0)
        fail(root.child("components"), "no component has role sonotrode, and shot.count is " + std::to_string(d.shot.count) +
                                           "; expected a sonotrode to place the shot on (or shot.count: 0 with sources)");
    if (d.shot.count == 0 && d.sources.empty())
        fail(root.child("shot").child("count"),
             "expected at least 1 shot, or sources that emit them (shot.count is 0 and the "
             "scene has no sources)");
    if (sonotrodes > 0 && chambers == 0)
        fail(root.child("components"), "no component has role chamber; expected at least one chamber around the sonotrode");
}

// until_coverage needs a logged part with a yield stress (coverage counts dents), and its names
// must name such parts and their regions.
void check_until_coverage(const Cursor& process, const SceneDescription& d) {
    if (!d.process.until_coverage) return;
    const auto covered = [&d](const ComponentDesc& c) {
        const bool logged =
            std::find(d.output.logged_components.begin(), d.output.logged_components.end(), c.name) != d.output.logged_components.end();
        const auto m = std::find_if(d.materials.begin(), d.materials.end(), [&c](const MaterialDesc& x) { return x.name == c.material; });
        return logged && m != d.materials.end() && m->yield_stress_pa.has_value();
    };
    std::string parts;
    for (const ComponentDesc& c : d.components)
        if (covered(c)) parts += (parts.empty() ? "" : ", ") + c.name;
    if (parts.empty())
        fail(process.child("until_coverage"),
             "coverage needs a logged part whose material has a yield_stress (the dents' size, eq. 10); expected one in `output.log`");
    for (const std::string& name : d.process.until_coverage_of) {
        if (std::count(d.process.until_coverage_of.begin(), d.process.until_coverage_of.end(), name) > 1)
            fail(process.child("until_coverage_of"), "'" + name + "' is listed twice; expected each area once");
        const std::size_t slash = name.find('/');
        const std::string part = name.substr(0, slash);
        const auto c = std::find_if(d.components.begin(), d.components.end(), [&part](const ComponentDesc& x) { return x.name == part; });
        if (c == d.components.end() || !covered(*c))
            fail(process.child("until_coverage_of"),
                 "unknown part '" + part + "' in '" + name +
                     "'; expected `part` or `part/region` of a logged part with a yield stress: " + parts);
        if (slash == std::string::npos) continue;
        const std::string region = name.substr(slash + 1);
        std::string names;  // the regions coverage counts: an excluded one is never waited for
        bool found = false;
        for (const RegionDesc& r : c->regions)
            for (const std::string& n : region_names(r)) {
                if (n == region && r.exclude)
                    fail(process.child("until_coverage_of"), "region '" + name +
                                                                 "' is excluded (`exclude: true`): coverage does not count it, so no run "
                                                                 "can wait for it; expected a region coverage counts");
                if (r.exclude) continue;
                found = found || n == region;
                names += (names.empty() ? "" : ", ") + n;
            }
        if (!found)
            fail(process.child("until_coverage_of"), "part '" + part + "' has no region '" + region + "'; expected one of: " +
                                                         (names.empty() ? std::string("(none: it has no regions)") : names));
    }
}

SceneDescription build_scene(const Cursor& root, const std::filesystem::path& scene_dir) {
    SceneDescription d;
    d.name = read_text(root.child("name"));
    d.process = read_process(root.child("process"));
    d.accuracy = read_accuracy(root.child("accuracy"));
    d.air = read_air(root.child("air"));
    if (d.air.drag) {
        // The event scheme's kernels solve exact parabolas: a scene whose flights are not runs with
        // time stepping, which it gets by default and must not be refused silently.
        if (d.accuracy.scheme_given && d.accuracy.scheme != SteppingScheme::step)
            fail(root.child("accuracy").child("scheme"),
                 std::string("the ") + scheme_name(d.accuracy.scheme) +
                     " scheme needs exact parabolic flights, and air.drag is on; expected `step` (or leave the scheme out: "
                     "a scene with air drag runs with time stepping)");
        d.accuracy.scheme = SteppingScheme::step;
    }
    d.materials = read_materials(root.child("materials"));
    d.shot = read_shot(root.child("shot"), d.materials);
    d.contacts = read_contacts(root.child("contacts"), d.materials);
    d.components = read_components(root.child("components"), scene_dir, d.materials);
    const double shot_mass_kg = mean_shot_mass_kg(d.shot);  // a mass flow of a mix: the mean shot
    const Vec3 up = d.process.gravity_m_per_s2.norm() > 0.0 ? Vec3(-d.process.gravity_m_per_s2.normalized()) : Vec3(Vec3::UnitZ());
    read_flow(root.child("sources"), root.child("sinks"), d.process.duration_s, shot_mass_kg, up, scene_dir, d.sources, d.sinks);
    check_shot_origin(root, d);
    d.output = read_output(root.child("output"), d.components, d.process.duration_s);
    check_until_coverage(root.child("process"), d);
    d.render = read_render(root.child("render"));
    return d;
}

// "amplitude: 25 is 25 m; did you mean 25 um?": the unit a slip most likely dropped.
SceneDescription::Warning plain_number_warning(const PlainQuantity& q) {
    const std::string si(si_unit(q.dimension));
    std::string meant;
    double value = 0.0;
    std::from_chars(q.text.data(), q.text.data() + q.text.size(), value);
    if (q.dimension == Dimension::length && std::abs(value) >= 1.0) {  // 25 or 18: mm or um dropped; 0.02 may be meant in m
        const bool small = q.field.find("amplitude") != std::string::npos;
        meant = "; did you mean " + q.text + (small ? " um" : " mm") + "?";
    }
    return {q.where, q.field,
            "the plain number " + q.text + " is read in SI units: " + q.text + " " + si + ", while this scene gives units elsewhere" +
                meant + " (write the unit to silence this)"};
}

}  // namespace

SceneDescription parse_scene_text(const std::string& yaml_text, const std::string& virtual_path,
                                  const std::vector<std::string>& overrides) {
    SceneContext context;
    context.file = virtual_path;
    YAML::Node root = parse_yaml(yaml_text, virtual_path);
    try {
        apply_overrides(root, overrides, context);
        const Cursor top = root_cursor(context, root);
        check_structure(top);
        const std::filesystem::path scene_dir = std::filesystem::absolute(virtual_path).parent_path();
        SceneDescription d = build_scene(top, scene_dir);
        d.source_file = virtual_path;
        // A plain number in the file is a slip when the file writes units elsewhere (a file all in
        // SI, such as a resolved scene, stays quiet whatever unit an override writes); one in an
        // override, when the file or another override does.
        for (const PlainQuantity& q : context.plain_quantities)
            if (q.where.file == override_file_name ? context.units_given : context.units_in_file)
                d.warnings.push_back(plain_number_warning(q));
        return d;
    } catch (const YAML::Exception& e) {
        // The checks above should leave yaml-cpp nothing to throw; never let it escape as a crash.
        const int line = e.mark.line >= 0 ? e.mark.line + 1 : 0;
        throw InputError(SourceLocation{virtual_path, line, 0}, "", "unexpected YAML problem: " + e.msg);
    }
}

SceneDescription parse_scene_file(const std::string& path, const std::vector<std::string>& overrides) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(SourceLocation{path, 0, 0}, "", "cannot read the scene file: it does not exist or is not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(SourceLocation{path, 0, 0}, "", "cannot read the scene file: it cannot be opened");
    std::ostringstream text;
    text << in.rdbuf();
    return parse_scene_text(text.str(), path, overrides);
}

}  // namespace peensim
