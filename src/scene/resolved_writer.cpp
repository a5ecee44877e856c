#include "scene/resolved_writer.h"

#include <cmath>

#include <algorithm>
#include <array>
#include <cstdio>
#include <stdexcept>

#include "common/cad_file.h"
#include "common/file_digest.h"
#include "common/fnv_hash.h"
#include "common/units.h"
#include "scene/schema.h"

namespace peensim {
namespace {

// Text as a YAML scalar: plain when it cannot be misread, double-quoted otherwise.
std::string yaml_text(const std::string& s) {
    bool plain = !s.empty() && s.front() != '-' && s.front() != '.';
    for (char c : s) {
        const bool safe =
            (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.' || c == '/';
        plain = plain && safe;
    }
    for (const char* word : {"null", "Null", "NULL", "true", "True", "TRUE", "false", "False", "FALSE"}) plain = plain && s != word;
    if (plain) return s;
    std::string out = "\"";
    for (unsigned char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += static_cast<char>(c);
        } else if (c < 0x20) {
            std::array<char, 8> buf{};
            std::snprintf(buf.data(), buf.size(), "\\x%02x", c);
            out += buf.data();
        } else {
            out += static_cast<char>(c);
        }
    }
    return out + "\"";
}

std::string si_text(double v) { return format_si(v); }

std::string vec(const Vec3& v) {
    std::string out = "[";  // appended piece by piece: GCC 12 warns falsely on "literal" + string&&
    out += si_text(v.x()) + ", " + si_text(v.y()) + ", " + si_text(v.z()) + "]";
    return out;
}

std::string unit_comment(Dimension d) { return "  # " + std::string(si_unit(d)); }

std::string mesh_unit_name(double metres_per_unit) {
    for (std::string_view unit : split_choices(find_schema_entry("components[].mesh_unit")->choices))
        if (parse_quantity("1 " + std::string(unit), Dimension::length) == metres_per_unit) return std::string(unit);
    throw std::invalid_argument("resolved_scene_yaml: mesh_unit_m " + si_text(metres_per_unit) + " is none of the scene file's mesh units");
}

void write_header(std::string& y, const SceneDescription& s) {
    y += "# Resolved scene: every default filled in, SI units, absolute paths.\n";
    y += "name: " + yaml_text(s.name) + "\n";
    y += "process:\n";
    y += "  duration: " + si_text(s.process.duration_s) + unit_comment(Dimension::time) + "\n";
    y += "  gravity: " + vec(s.process.gravity_m_per_s2) + unit_comment(Dimension::acceleration) + "\n";
    y += "  seed: " + std::to_string(s.process.seed) + "\n";
    if (s.process.until_coverage) {
        y += "  until_coverage: " + si_text(*s.process.until_coverage) + "\n";
        std::string of;
        for (const std::string& n : s.process.until_coverage_of) of += (of.empty() ? "" : ", ") + yaml_text(n);
        if (!of.empty()) y += "  until_coverage_of: [" + of + "]\n";
    }
    y += "accuracy:\n";
    y += "  travel_fraction: " + si_text(s.accuracy.travel_fraction) + "  # of the shot radius\n";
    y += "  impact_speed: " + si_text(s.accuracy.impact_speed_m_per_s) + unit_comment(Dimension::speed) + "\n";
    y += std::string("  scheme: ") + scheme_name(s.accuracy.scheme) + "\n";
    y += "  soft_steps_per_contact: " + si_text(s.accuracy.soft_steps_per_contact) + "  # per Hertz contact time (soft scheme)\n";
}

void write_shot(std::string& y, const ShotDesc& shot) {
    y += "shot:\n";
    y += "  count: " + std::to_string(shot.count) + "\n";
    if (!shot.sizes_given) {
        y += "  diameter: " + si_text(shot.sizes.front().diameter_m) + unit_comment(Dimension::length) + "\n";
    } else {
        y += std::string("  fractions_by: ") + (shot.fractions_by_mass ? "mass" : "count") + "\n";
        y += "  sizes:\n";
        for (const ShotSizeDesc& s : shot.sizes)
            y += "    - {diameter: " + si_text(s.diameter_m) + ", fraction: " + si_text(s.fraction) + "}" +
                 unit_comment(Dimension::length) + "\n";
    }
    if (shot.material.empty())
        y += "  density: " + si_text(shot.density_kg_per_m3) + unit_comment(Dimension::density) + "\n";
    else
        y += "  material: " + yaml_text(shot.material) + "  # density " + si_text(shot.density_kg_per_m3) + " kg/m3\n";
    if (shot.initial == InitialVelocityKind::vector)
        y += "  initial_velocity: " + vec(shot.initial_velocity_m_per_s) + unit_comment(Dimension::speed) + "\n";
    else if (shot.initial == InitialVelocityKind::random_upward)
        y += "  initial_speed: " + si_text(shot.initial_speed_m_per_s) + unit_comment(Dimension::speed) + "\n";
    else
        y += "  # initially at rest\n";
}

void write_air(std::string& y, const AirDesc& air) {
    y += "air:\n";
    y += std::string("  drag: ") + (air.drag ? "sphere" : "none") + "\n";
    y += "  density: " + si_text(air.density_kg_per_m3) + unit_comment(Dimension::density) + "\n";
    y += "  viscosity: " + si_text(air.viscosity_pa_s) + unit_comment(Dimension::viscosity) + "\n";
    if (air.drag_coefficient) y += "  drag_coefficient: " + si_text(*air.drag_coefficient) + "\n";
    if (air.rebound_scatter) {
        y += "  rebound_scatter:\n";
        y += "    spread: " + si_text(air.rebound_scatter->spread_rad) + unit_comment(Dimension::angle) + "\n";
        y += "    min_reynolds: " + si_text(air.rebound_scatter->min_reynolds) + "\n";
        y += "    min_speed: " + si_text(air.rebound_scatter->min_speed_m_per_s) + unit_comment(Dimension::speed) + "\n";
    }
}

// A source's rate, as the scene gave it (a mass flow, or shot per second).
void write_rate(std::string& y, const SourceDesc& d) {
    if (d.mass_flow_kg_per_s)
        y += "    mass_flow: " + si_text(*d.mass_flow_kg_per_s) + unit_comment(Dimension::mass_flow) + "  # " + si_text(d.rate_per_s) +
             " shot per s\n";
    else
        y += "    rate: " + si_text(d.rate_per_s) + "  # shot per s\n";
}

// What a scene's hash leaves out of the output block: the analysis' settings (they do not change
// the run), and the shot-position series when there is none (scenes without one keep the hash
// they had before the series existed). A series is hashed: a run resumes only with the interval
// its files were written at.
// What it puts in place of a mesh file's path: the file's bytes (common/file_digest.h), so that a
// mesh re-exported to the same path changes the hash and a copy of it elsewhere does not. The
// resolved scene writes the path with the same digest in a comment: what a later refusal compares
// each file's bytes with (scene_difference.h).
enum class OutputSettings { all, hashed };

std::string mesh_text(const std::string& path, OutputSettings settings) {
    return settings == OutputSettings::hashed ? yaml_text(file_digest_text(path))
                                              : yaml_text(path) + std::string(kMeshDigestComment) + file_digest_text(path);
}

// Sources and sinks, only when the scene has them (most have neither).
void write_flow(std::string& y, const SceneDescription& s, OutputSettings settings) {
    if (!s.sources.empty()) y += "sources:\n";
    for (const SourceDesc& d : s.sources) {
        y += "  - name: " + yaml_text(d.name) + "\n";
        if (d.kind == SourceKind::hopper) {
            y += "    kind: hopper\n";
            y += "    opening_min: " + vec(d.opening->lo_m) + unit_comment(Dimension::length) + "\n";
            y += "    opening_max: " + vec(d.opening->hi_m) + unit_comment(Dimension::length) + "\n";
            write_rate(y, d);
            y += "    start: " + si_text(d.start_s) + unit_comment(Dimension::time) + "\n";
            y += "    stop: " + si_text(d.stop_s) + unit_comment(Dimension::time) + "\n";
            continue;
        }
        if (d.aim) {
            y += "    target: " + vec(d.aim->target_m) + unit_comment(Dimension::length) + "\n";
            y += "    distance: " + si_text(d.aim->distance_m) + unit_comment(Dimension::length) + "\n";
            y += "    angle_of_attack: " + si_text(d.aim->angle_of_attack_rad) + unit_comment(Dimension::angle) + "\n";
            y += "    target_normal: " + vec(d.aim->target_normal) + "\n";
            y += "    azimuth: " + si_text(d.aim->azimuth_rad) + unit_comment(Dimension::angle) + "\n";
            y += "    # position: " + vec(d.position_m) + " m, direction: " + vec(d.direction) + " (from the target)\n";
        } else {
            y += "    position: " + vec(d.position_m) + unit_comment(Dimension::length) + "\n";
            y += "    direction: " + vec(d.direction) + "\n";
        }
        y += "    speed: " + si_text(d.speed_m_per_s) + unit_comment(Dimension::speed) + "\n";
        y += "    speed_spread: " + si_text(d.speed_spread) + "\n";
        if (d.air_speed_m_per_s) y += "    air_speed: " + si_text(*d.air_speed_m_per_s) + unit_comment(Dimension::speed) + "\n";
        write_rate(y, d);
        y += "    exit_radius: " + si_text(d.exit_radius_m) + unit_comment(Dimension::length) + "\n";
        y += "    spread: " + si_text(d.spread_rad) + unit_comment(Dimension::angle) + "\n";
        y += "    start: " + si_text(d.start_s) + unit_comment(Dimension::time) + "\n";
        y += "    stop: " + si_text(d.stop_s) + unit_comment(Dimension::time) + "\n";
    }
    if (!s.sinks.empty()) y += "sinks:\n";
    for (const SinkDesc& d : s.sinks) {
        y += "  - name: " + yaml_text(d.name) + "\n";
        y += std::string("    region: ") + (d.region == SinkRegion::box ? "box" : d.region == SinkRegion::mesh ? "mesh" : "outside") + "\n";
        if (d.region == SinkRegion::mesh) {
            y += "    mesh: " + mesh_text(d.mesh_path, settings) + "\n";
            if (!is_cad_file(d.mesh_path))  // (a STEP/IGES file states its own unit)
                y += "    mesh_unit: " + mesh_unit_name(d.mesh_unit_m) + "  # " + si_text(d.mesh_unit_m) + " m per mesh unit\n";
            y += "    translation: " + vec(d.translation_m) + unit_comment(Dimension::length) + "\n";
        }
        if (d.region != SinkRegion::box) continue;
        y += "    min: " + vec(d.min_m) + unit_comment(Dimension::length) + "\n";
        y += "    max: " + vec(d.max_m) + unit_comment(Dimension::length) + "\n";
    }
}

void write_materials_and_contacts(std::string& y, const SceneDescription& s) {
    y += s.materials.empty() ? "materials: {}\n" : "materials:\n";
    for (const MaterialDesc& m : s.materials) {
        if (!m.density_kg_per_m3 && !m.yield_stress_pa && !m.youngs_modulus_pa && !m.poisson_ratio) {
            y += "  " + yaml_text(m.name) + ": {}\n";
            continue;
        }
        y += "  " + yaml_text(m.name) + ":\n";
        if (m.density_kg_per_m3) y += "    density: " + si_text(*m.density_kg_per_m3) + unit_comment(Dimension::density) + "\n";
        if (m.yield_stress_pa) y += "    yield_stress: " + si_text(*m.yield_stress_pa) + unit_comment(Dimension::stress) + "\n";
        if (m.youngs_modulus_pa) y += "    youngs_modulus: " + si_text(*m.youngs_modulus_pa) + unit_comment(Dimension::stress) + "\n";
        if (m.poisson_ratio) y += "    poisson_ratio: " + si_text(*m.poisson_ratio) + "\n";
    }
    y += "contacts:\n";
    for (const ContactPairDesc& c : s.contacts) {
        y += "  " + yaml_text(c.key) + ":\n";
        y += "    law: " + c.law + "\n";
        for (const LawParameterValue& p : c.parameters) {
            const SchemaEntry* e = find_schema_entry("contacts.*." + p.name);
            const Dimension d = e != nullptr ? e->dimension : Dimension::dimensionless;
            std::string text;
            for (double v : p.values) text += (text.empty() ? "" : ", ") + si_text(v);
            if (e != nullptr && e->kind == ValueKind::quantity_list) text = "[" + text + "]";
            y += "    " + p.name + ": " + text + (d == Dimension::dimensionless ? "" : unit_comment(d)) + "\n";
        }
    }
}

std::string matrix_text(const Mat3& m) {
    std::string out = "[";
    for (int r = 0; r < 3; ++r)
        out += std::string(r ? ", " : "") + "[" + si_text(m(r, 0)) + ", " + si_text(m(r, 1)) + ", " + si_text(m(r, 2)) + "]";
    return out + "]";
}

// One region as a flow map on one line (SI values; angles in rad).
std::string frame_text(const AxisAngleFrame& f) {
    return "axis_point: " + vec(f.axis_point_m) + ", axis_direction: " + vec(f.axis_direction) + ", reference: " + vec(f.reference);
}

// A distance range's min and max (no max: no upper bound).
std::string distance_range_text(double min_m, double max_m) {
    return "min: " + si_text(min_m) + (std::isfinite(max_m) ? ", max: " + si_text(max_m) : std::string());
}

std::string region_text(const RegionDesc& r) {
    std::string out = "{name: " + yaml_text(r.name);
    if (r.sector)
        out += ", sector: {" + frame_text(r.sector->frame) + ", from: " + si_text(r.sector->from_rad) +
               ", to: " + si_text(r.sector->to_rad) + "}";
    if (r.sectors)
        out += ", sectors: {" + frame_text(r.sectors->frame) + ", count: " + std::to_string(r.sectors->count) +
               ", width: " + si_text(r.sectors->width_rad) + ", offset: " + si_text(r.sectors->offset_rad) +
               ", name_prefix: " + yaml_text(r.sectors->name_prefix) + "}";
    if (r.box) out += ", box: {min: " + vec(r.box->min_m) + ", max: " + vec(r.box->max_m) + "}";
    if (r.half_space) out += ", half_space: {point: " + vec(r.half_space->point_m) + ", normal: " + vec(r.half_space->normal) + "}";
    if (r.distance_to_axis)
        out += ", distance_to_axis: {axis_point: " + vec(r.distance_to_axis->axis_point_m) +
               ", axis_direction: " + vec(r.distance_to_axis->axis_direction) + ", " +
               distance_range_text(r.distance_to_axis->min_m, r.distance_to_axis->max_m) + "}";
    if (r.distance_to_point)
        out += ", distance_to_point: {point: " + vec(r.distance_to_point->point_m) + ", " +
               distance_range_text(r.distance_to_point->min_m, r.distance_to_point->max_m) + "}";
    if (r.facing) out += ", facing: {direction: " + vec(r.facing->direction) + ", within: " + si_text(r.facing->within_rad) + "}";
    if (r.group) out += ", group: " + yaml_text(*r.group);
    if (r.exclude) out += ", exclude: true";
    return out + "}  # m, rad";
}

void write_component(std::string& y, const ComponentDesc& k, OutputSettings settings) {
    y += "  - name: " + yaml_text(k.name) + "\n";
    y += std::string("    role: ") + role_name(k.role) + "\n";
    y += "    mesh: " + mesh_text(k.mesh_path, settings) + "\n";
    if (is_cad_file(k.mesh_path))  // its own unit; the tessellation instead
        y += "    tessellation: {chordal: " + si_text(k.tessellation.chordal_m) + ", angular: " + si_text(k.tessellation.angular_rad) +
             "}  # m, rad\n";
    else
        y += "    mesh_unit: " + mesh_unit_name(k.mesh_unit_m) + "  # " + si_text(k.mesh_unit_m) + " m per mesh unit\n";
    y += "    translation: " + vec(k.translation_m) + unit_comment(Dimension::length) + "\n";
    const Eigen::AngleAxisd aa(k.rotation);
    y += "    rotation:  # " + si_text(aa.angle()) + " rad about " + vec(aa.axis()) + "\n";
    y += "      matrix: " + matrix_text(k.rotation) + "\n";
    if (!k.material.empty()) y += "    material: " + yaml_text(k.material) + "\n";
    if (k.vibration) {
        const VibrationDesc& v = *k.vibration;
        y += "    vibration:\n";
        y += "      amplitude: " + si_text(v.amplitude_m) + unit_comment(Dimension::length) + "\n";
        y += "      frequency: " + si_text(v.frequency_hz) + unit_comment(Dimension::frequency) + "\n";
        y += "      phase: " + si_text(v.phase_rad) + unit_comment(Dimension::angle) + "\n";
        if (v.axis)
            y += "      axis: " + vec(*v.axis) + "\n";
        else
            y += "      # axis: the sonotrode's mean face normal (found when the model is compiled)\n";
    }
    if (k.almen) {
        const AlmenDesc& a = *k.almen;
        y += "    almen:\n";
        y += "      face_normal: " + vec(a.face_normal) + "\n";
        if (a.saturation_arc_height_m) {
            y += "      saturation_arc_height: " + si_text(*a.saturation_arc_height_m) + unit_comment(Dimension::length) + "\n";
            y += "      dose_constant: " + si_text(*a.dose_constant_J_per_m2) + unit_comment(Dimension::energy_per_area) + "\n";
        } else if (!a.calibration) {
            y += "      # saturation_arc_height, dose_constant: not calibrated (dose only)\n";
        }
        if (a.calibration) {
            const AlmenCalibrationDesc& m = *a.calibration;
            y += "      calibration:\n";
            y += "        saturation_arc_height: " + si_text(m.saturation_arc_height_m) + unit_comment(Dimension::length) + "\n";
            y += "        time_constant: " + si_text(m.time_constant_s) + unit_comment(Dimension::time) + "\n";
            y += "        shape: " + si_text(m.shape) + "\n";
            y += "        dent_size: " + si_text(m.dent_size_m) + unit_comment(Dimension::length) + "\n";
            y += "        covering_rate: " + si_text(m.covering_rate_per_s) + unit_comment(Dimension::frequency) + "\n";
            if (!m.strip.empty()) y += "        strip: " + m.strip + "\n";
        }
    }
    if (!k.regions.empty()) y += "    regions:\n";
    for (const RegionDesc& r : k.regions) y += "      - " + region_text(r) + "\n";
    if (!k.rotation_motion) {
        y += "    motion: static\n";
        return;
    }
    const RotationDesc& r = *k.rotation_motion;
    y += "    motion:\n";
    y += "      type: rotating\n";
    y += "      axis_point: " + vec(r.axis_point_m) + unit_comment(Dimension::length) + "\n";
    y += "      axis_direction: " + vec(r.axis_direction) + "\n";
    y += "      speed: " + si_text(r.speed_rad_per_s) + unit_comment(Dimension::angular_speed) + "\n";
}

void write_output(std::string& y, const OutputDesc& o, OutputSettings settings) {
    y += "output:\n";
    std::string log;
    for (const std::string& n : o.logged_components) log += (log.empty() ? "" : ", ") + yaml_text(n);
    y += "  log: [" + log + "]\n";
    if (!o.directory.empty())
        y += "  directory: " + yaml_text(o.directory) + "\n";
    else
        y += "  # directory: given on the command line\n";
    y += "  checkpoint_interval: " + si_text(o.checkpoint_interval_s) + unit_comment(Dimension::time) + "\n";
    if (o.shot_positions_s)
        y += "  shot_positions: " + si_text(*o.shot_positions_s) + unit_comment(Dimension::time) + "\n";
    else if (settings == OutputSettings::all)
        y += "  # shot_positions: off\n";
    if (settings == OutputSettings::all) y += "  coverage_steps: " + std::to_string(o.coverage_steps) + "\n";
    if (o.smoothing_radius_m)
        y += "  smoothing_radius: " + si_text(*o.smoothing_radius_m) + unit_comment(Dimension::length) + "\n";
    else if (settings == OutputSettings::all)
        y += "  # smoothing_radius: chosen by the analysis (dent size, impact density)\n";
}

void write_render(std::string& y, const RenderDesc& r) {
    y += "render:\n";
    y += "  width: " + std::to_string(r.width_px) + "\n";
    y += "  height: " + std::to_string(r.height_px) + "\n";
    y += "  fps: " + std::to_string(r.fps) + "\n";
    y += "  slow_motion: " + si_text(r.slow_motion_s) + unit_comment(Dimension::time) + "\n";
    y += "  start: " + si_text(r.start_s) + unit_comment(Dimension::time) + "\n";
    y += "  duration: " + si_text(r.duration_s) + unit_comment(Dimension::time) + "\n";
    y += "  camera:\n";
    if (r.camera_position_m)
        y += "    position: " + vec(*r.camera_position_m) + unit_comment(Dimension::length) + "\n";
    else
        y += "    # position: automatic framing of the chamber\n";
    if (r.camera_look_at_m)
        y += "    look_at: " + vec(*r.camera_look_at_m) + unit_comment(Dimension::length) + "\n";
    else
        y += "    # look_at: the chamber's centre\n";
    y += "    up: " + vec(r.camera_up) + "\n";
    y += "    fov: " + si_text(r.fov_rad) + unit_comment(Dimension::angle) + "\n";
    y += "  speed_scale: " + si_text(r.speed_scale_m_per_s) + unit_comment(Dimension::speed) + "\n";
    y += std::string("  video: ") + (r.video ? "mp4" : "none") + "\n";
}

std::string scene_yaml(const SceneDescription& s, OutputSettings settings) {
    std::string y;
    write_header(y, s);
    write_shot(y, s.shot);
    write_air(y, s.air);
    write_materials_and_contacts(y, s);
    y += "components:\n";
    for (const ComponentDesc& k : s.components) write_component(y, k, settings);
    write_flow(y, s, settings);
    write_output(y, s.output, settings);
    if (s.render) write_render(y, *s.render);
    return y;
}

}  // namespace

std::string resolved_scene_yaml(const SceneDescription& s) { return scene_yaml(s, OutputSettings::all); }

std::string scene_hash_hex(std::uint64_t hash) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
    return text;
}

std::string hashed_scene_yaml(const SceneDescription& s) {
    // Rendering, the checkpoint interval and the maps' smoothing do not change what is simulated:
    // a run may be resumed with other settings for them.
    SceneDescription simulated = s;
    simulated.render.reset();
    simulated.output.checkpoint_interval_s = 0.0;
    // Materials and contact pairs are found by name: the order they are written in is not the run's.
    std::sort(simulated.materials.begin(), simulated.materials.end(),
              [](const MaterialDesc& a, const MaterialDesc& b) { return a.name < b.name; });
    std::sort(simulated.contacts.begin(), simulated.contacts.end(),
              [](const ContactPairDesc& a, const ContactPairDesc& b) { return a.key < b.key; });
    return scene_yaml(simulated, OutputSettings::hashed);
}

std::uint64_t scene_hash(const SceneDescription& s) { return fnv1a64(hashed_scene_yaml(s)); }

std::string resolved_region_text(const RegionDesc& region) { return region_text(region); }

}  // namespace peensim
