#include "app/new_scene/new_scene_job.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <optional>
#include <ostream>

#include "app/new_scene/scene_design.h"
#include "app/new_scene/scene_yaml.h"
#include "app/report_errors.h"
#include "common/cad_file.h"
#include "common/input_error.h"
#include "common/units.h"
#include "geometry/cylinder_mesh.h"
#include "geometry/mesh_checks.h"
#include "geometry/mesh_loader.h"
#include "geometry/part_envelope.h"
#include "geometry/stepped_chamber_mesh.h"
#include "geometry/stl_writer.h"
#include "model/plausibility.h"
#include "output/atomic_file.h"

namespace peensim {

namespace fs = std::filesystem;

namespace {

// A part under 5 shot across (or 1 mm) is a unit mistake (an inch file read in mm) or shot far too large.
constexpr double kSmallestPartM = kSmallestPlausibleMesh_m;  // m
constexpr double kSmallestPartShots = 5.0;
constexpr double kLargestPartM = kLargestPlausibleMesh_m;  // m: no USP chamber holds a part larger than this
constexpr double kFastestRpm = 3000.0;                     // rev/min: beyond any USP fixture
constexpr int kSegments = 128;                             // around the chamber and the sonotrode, as the gear case's

InputError option_error(const std::string& option, const std::string& problem) { return InputError({"peensim new"}, option, problem); }

// `text` as the shell reads it back: quoted when it holds anything but [A-Za-z0-9_./+-].
std::string shell_word(const std::string& text) {
    const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](unsigned char c) {
        return std::isalnum(c) || c == '_' || c == '.' || c == '/' || c == '+' || c == '-';
    });
    if (plain) return text;
    std::string q = "'";
    for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// A sonotrode wider than this or more shot than this is a unit mistake more often than a part:
// said, not refused (a large disc is peened on large sonotrodes).
constexpr double kWidestLikelySonotrodeM = 0.2;
constexpr int kMostLikelyShot = 5000;

std::string mm_one_decimal(double metres) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.1f", metres * 1e3);
    return std::string(buf) == "-0.0" ? "0.0" : buf;
}

// What the regions are, said in a line ("the two ends and 5 of 8 sectors about the axis; left out,
// holding none of its surface: sector-0 sector-1 sector-2").
std::string regions_text(const ProposedRegions& regions, const NewSceneRequest& request) {
    const auto count = [&](const char* prefix) {
        std::size_t n = 0;
        for (const RegionDesc& e : regions.entries)
            if (e.name.rfind(prefix, 0) == 0) n += e.sectors ? static_cast<std::size_t>(e.sectors->count) : 1;
        return n;
    };
    std::string text;
    if (request.turning_axis) {
        const std::size_t ends = count("end-"), sectors = count("sector");
        text = (ends == 2   ? "the two ends"
                : ends == 1 ? "one end"
                            : "no end") +
               std::string(" and ") + (sectors == kProposedSectors ? "" : std::to_string(sectors) + " of ") +
               std::to_string(kProposedSectors) + " sectors about the axis";
    } else {
        text = "by facing direction (" + std::to_string(regions.entries.size()) + ")";
    }
    if (!regions.left_out.empty()) {
        text += "; left out, holding none of its surface:";
        for (const std::string& name : regions.left_out) text += " " + name;
    }
    return text;
}

// A name the scene accepts ([A-Za-z0-9_-]+) from the part file's name.
std::string component_name(const fs::path& part) {
    std::string name;
    for (char c : part.stem().string()) name += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-') ? c : '-';
    return name.empty() ? "part" : name;
}

// Layers of quads so that the chamber's quads are at most kQuadAspect times as tall as wide (the
// shipped gear chamber's upper wall: 2.5); finer only costs triangles (a wall is flat along z).
constexpr double kQuadAspect = 2.5;
int layers_for(double height_m, double radius_m) {
    const double side_m = kQuadAspect * 2.0 * M_PI * radius_m / kSegments;
    return std::max(1, static_cast<int>(std::ceil(height_m / side_m)));
}

// The path the scene names `target` by: relative to the scene's folder when they share more than
// the root (a project's scenes/ and parts/), else absolute (a part in /home/... seen from /tmp).
std::string relative_to(const fs::path& target, const fs::path& folder) {
    std::error_code ec;
    const fs::path absolute_target = fs::weakly_canonical(fs::absolute(target), ec);
    const fs::path absolute_folder = fs::weakly_canonical(fs::absolute(folder), ec);
    const fs::path rel = absolute_target.lexically_relative(absolute_folder);
    const fs::path below_root = absolute_folder.relative_path();
    const auto depth = std::distance(below_root.begin(), below_root.end());
    long climbs = 0;
    for (const fs::path& part : rel)
        if (part == "..") ++climbs;
    return rel.empty() || climbs >= depth ? absolute_target.generic_string() : rel.generic_string();
}

int run_new_scene(const NewSceneOptions& o, std::ostream& out) {
    // The request.
    // A STEP or IGES file states its unit (the reader converts); a mesh file's is --unit, mm by default.
    const bool cad = is_cad_file(o.part_path);
    if (cad && !o.unit.empty())
        throw option_error("--unit", "a STEP or IGES file states its own length unit, which is used: leave --unit out");
    const std::string unit = o.unit.empty() ? "mm" : o.unit;
    if (unit != "mm" && unit != "cm" && unit != "m" && unit != "um" && unit != "in")
        throw option_error("--unit",
                           "expected mm, cm, m, um or in (the part file's length unit; STL has none of its own), got '" + unit + "'");
    const double unit_m = parse_quantity("1 " + unit, Dimension::length);
    std::string unit_said = cad ? "the file's unit" : unit == "in" ? "inches" : unit;  // a CAD file's named once read
    const PartMaterial* material = find_part_material(o.material);
    if (!material) throw option_error("--material", "expected one of " + part_material_options() + ", got '" + o.material + "'");
    NewSceneRequest request;
    try {
        request.shot_diameter_m = parse_quantity(o.shot_diameter, Dimension::length, "mm");
    } catch (const QuantityError& e) {
        throw option_error("--shot-diameter", e.what());
    }
    if (!(request.shot_diameter_m >= 0.1e-3 && request.shot_diameter_m <= 10e-3))
        throw option_error("--shot-diameter", "expected a shot between 0.1 and 10 mm, got '" + o.shot_diameter + "'");
    if (!o.rotate_about.empty()) {
        if (o.rotate_about == "x")
            request.turning_axis = Axis::x;
        else if (o.rotate_about == "y")
            request.turning_axis = Axis::y;
        else if (o.rotate_about == "z")
            request.turning_axis = Axis::z;
        else
            throw option_error("--rotate-about",
                               "expected x, y or z (an axis of the part's own frame, through its centre), got '" + o.rotate_about + "'");
        if (o.rpm.empty()) throw option_error("--rpm", "a turning part needs its speed, e.g. --rpm 30");
        std::string rpm_text = o.rpm;
        double rpm = 0.0;
        if (!parse_plain_number(rpm_text, rpm)) {
            try {
                rpm = parse_quantity(rpm_text, Dimension::angular_speed) * 60.0 / (2.0 * M_PI);
            } catch (const QuantityError& e) {
                throw option_error("--rpm", e.what());
            }
        }
        if (!(rpm > 0.0 && rpm <= kFastestRpm))
            throw option_error("--rpm", "expected a speed above 0 and at most 3000 rpm, got '" + o.rpm + "'");
        request.rpm = rpm;
    } else if (!o.rpm.empty()) {
        throw option_error("--rpm", "a speed needs an axis to turn about: add --rotate-about x, y or z");
    }

    // The files: never over an existing one unless forced, never over the part.
    const fs::path part = o.part_path;
    const fs::path scene = o.scene_path.empty() ? fs::path(part.stem().string() + ".yaml") : fs::path(o.scene_path);
    if (scene.extension() != ".yaml" && scene.extension() != ".yml")
        throw option_error("-o", "expected a scene file name ending in .yaml, got '" + scene.string() + "'");
    const fs::path folder = scene.has_parent_path() ? scene.parent_path() : fs::path(".");
    // Beside the scene ("x-assets", not "./x-assets", for a scene in the current folder).
    const auto beside_scene = [&](const std::string& name) { return scene.has_parent_path() ? folder / name : fs::path(name); };
    const fs::path assets = beside_scene(scene.stem().string() + "-assets");
    const fs::path chamber_stl = assets / "chamber.stl", sonotrode_stl = assets / "sonotrode.stl";
    std::error_code ec;
    for (const fs::path& p : {scene, chamber_stl, sonotrode_stl}) {
        if (fs::exists(part) && fs::equivalent(part, p, ec))
            throw option_error("-o", "'" + p.string() + "' is the part itself: choose another scene name");
        if (fs::exists(p) && !o.force)
            throw option_error("-o", "'" + p.string() + "' exists; choose another scene name, or --force to write over it");
    }

    // The part and the design around it.
    if (std::error_code missing; !fs::exists(o.part_path, missing))
        throw InputError({o.part_path}, "PART", "no such file (looked for " + fs::absolute(o.part_path).string() + ")");
    const TriangleMesh mesh = load_mesh(o.part_path, unit_m);
    if (cad) unit_said = mesh.declared_unit.empty() ? "the file's unit (it names none)" : "the file's unit, " + mesh.declared_unit;
    const PartEnvelope envelope = part_envelope(mesh, request.turning_axis);
    const double largest = envelope.size_m.maxCoeff();
    const std::string size_text = mm_one_decimal(envelope.size_m.x()) + " x " + mm_one_decimal(envelope.size_m.y()) + " x " +
                                  mm_one_decimal(envelope.size_m.z()) + " mm";
    // A STEP or IGES file states its own unit (--unit is refused for it): the question is then
    // whether the file was exported in the unit it names.
    const char* unit_field = cad ? "PART" : "--unit";
    const std::string unit_question =
        cad ? "was the file exported in the unit it names (export it again in mm or m)?" : "is its unit right (--unit mm, cm, m, um, in)?";
    if (largest > kLargestPartM || largest < kSmallestPartM)
        throw InputError({o.part_path}, unit_field,
                         "read in " + unit_said + " the part is " + size_text + ": expected 1 mm to 2 m across; " + unit_question);
    if (largest < kSmallestPartShots * request.shot_diameter_m)
        throw InputError({o.part_path}, unit_field,
                         "read in " + unit_said + " the part is " + size_text + ", under 5 shot of " +
                             mm_one_decimal(request.shot_diameter_m) + " mm across: " + unit_question +
                             " Or is the shot too large (--shot-diameter)?");
    const SceneDesign design = design_scene(envelope, request);
    // The chamber around the part must itself be plausible: a scene that `peensim check` warns on
    // as a unit slip is no ready scene (a 1.5 m part made a 2.15 m chamber).
    const double chamber_m = std::max(2.0 * std::max(design.upper_radius_m, design.lower_radius_m), design.lid_z_m - design.bottom_z_m);
    if (chamber_m > kLargestPlausibleMesh_m)
        throw InputError({o.part_path}, unit_field,
                         "read in " + unit_said + " the part is " + size_text + ", and the chamber around it would be " +
                             mm_one_decimal(chamber_m) + " mm across, beyond the " + mm_one_decimal(kLargestPlausibleMesh_m) +
                             " mm `peensim check` takes for a unit slip; " + unit_question +
                             " A part this large "
                             "(over about " +
                             mm_one_decimal(largest * kLargestPlausibleMesh_m / chamber_m) +
                             " mm here) is peened in sections or by a moving sonotrode: write its scene by hand");
    const ProposedRegions regions = propose_regions(mesh, envelope, request.turning_axis);

    // The chamber and the sonotrode (mm files, as the shipped ones).
    SteppedChamberSpec chamber;
    chamber.lower_radius_m = design.lower_radius_m;
    chamber.upper_radius_m = design.upper_radius_m;
    chamber.bottom_z_m = design.bottom_z_m;
    chamber.step_z_m = design.step_z_m;
    chamber.lid_z_m = design.lid_z_m;
    chamber.segments = kSegments;
    chamber.lower_layers = layers_for(design.step_z_m - design.bottom_z_m, design.lower_radius_m);
    chamber.upper_layers = layers_for(design.lid_z_m - design.step_z_m, design.upper_radius_m);
    chamber.step_rings = layers_for(design.upper_radius_m - design.lower_radius_m, design.upper_radius_m);
    chamber.lid_rings = std::max(2, layers_for(design.upper_radius_m, design.upper_radius_m) / 4);
    CylinderSpec disk;
    disk.radius_m = design.sonotrode_radius_m;
    disk.height_m = design.sonotrode_thickness_m;
    disk.segments = kSegments;
    disk.axis = Axis::z;
    disk.center_m = Vec3(0.0, 0.0, -0.5 * design.sonotrode_thickness_m);
    disk.cap_rings = 6;
    const TriangleMesh chamber_mesh = stepped_tube_chamber(chamber), disk_mesh = cylinder(disk);

    NewSceneFiles files;
    files.part_name = component_name(part);
    if (files.part_name == "sonotrode" || files.part_name == "chamber") files.part_name += "-part";
    files.part_mesh = relative_to(part, folder);
    files.unit_name = cad ? "" : unit;
    files.chamber_mesh = relative_to(chamber_stl, folder);
    files.sonotrode_mesh = relative_to(sonotrode_stl, folder);
    files.command = o.command_line.empty() ? "peensim new " + o.part_path : o.command_line;
    const std::string yaml = new_scene_yaml(design, request, *material, regions, files);

    fs::create_directories(assets, ec);
    if (ec) throw std::runtime_error("cannot create " + assets.string() + ": " + ec.message());
    write_binary_stl(chamber_mesh, chamber_stl.string(), 1e-3, "chamber");
    write_binary_stl(disk_mesh, sonotrode_stl.string(), 1e-3, "sonotrode");
    write_file_atomically(scene.string(), yaml);

    // What it chose.
    const Vec3& sz = envelope.size_m;
    out << "peensim new: " << o.part_path << " (" << mesh.triangle_count() << " triangles, read in " << unit_said << ")\n";
    out << "  part       " << mm_one_decimal(sz.x()) << " x " << mm_one_decimal(sz.y()) << " x " << mm_one_decimal(sz.z()) << " mm, "
        << material->name << " (yield stress " << material->yield_stress_mpa << " MPa: edit it in the scene)\n";
    if (request.turning_axis)
        out << "  turning    about its " << o.rotate_about << " axis through its centre at " << request.rpm << " rpm: sweeps "
            << mm_one_decimal(envelope.swept_radius_m) << " mm about it\n";
    out << "  placed     centred over the sonotrode, its lowest point " << mm_one_decimal(design.standoff_m)
        << " mm above it (translation [" << mm_one_decimal(design.translation_m.x()) << ", " << mm_one_decimal(design.translation_m.y())
        << ", " << mm_one_decimal(design.translation_m.z()) << "] mm)\n";
    out << "  sonotrode  " << mm_one_decimal(2.0 * design.sonotrode_radius_m) << " mm across (the part's footprint "
        << mm_one_decimal(2.0 * envelope.footprint_radius_m) << " mm + " << mm_one_decimal(design.sonotrode_margin_m) << " mm a side), "
        << design.amplitude_m * 1e6 << " um at " << design.frequency_hz * 1e-3 << " kHz\n";
    out << "  chamber    " << mm_one_decimal(2.0 * design.upper_radius_m) << " mm across above z = " << mm_one_decimal(design.step_z_m)
        << " mm, " << mm_one_decimal(2.0 * design.lower_radius_m) << " mm below, lid at z = " << mm_one_decimal(design.lid_z_m) << " mm\n";
    out << "  shot       " << design.shot_count << " x " << request.shot_diameter_m * 1e3 << " mm steel ("
        << std::lround(100.0 * design.shot_fill) << " % of the sonotrode's face)\n";
    out << "  run        " << design.duration_s << " s"
        << (design.turns > 0 ? " (" + std::to_string(design.turns) + (design.turns == 1 ? " whole turn)" : " whole turns)") : "")
        << "; regions " << regions_text(regions, request) << "\n";
    out << "wrote " << scene.string() << ", " << chamber_stl.string() << ", " << sonotrode_stl.string() << "\n";
    // An open mesh runs, but its holes let shot into the part and its inside counts as surface.
    const EdgeReport edges = edge_report(mesh);
    if (edges.boundary_edges > 0 || edges.non_manifold_edges > 0)
        out << "warning: the part's mesh is not closed (" << edges.boundary_edges << " edges on one triangle only, "
            << edges.non_manifold_edges << " on three or more): shot can pass through its holes into the part, whose inside then\n"
            << "         counts as surface; export it as a closed solid (STEP, or an STL of the solid), or see `peensim check`\n";
    if (2.0 * design.sonotrode_radius_m > kWidestLikelySonotrodeM || design.shot_count > kMostLikelyShot)
        out << "warning: a " << mm_one_decimal(2.0 * design.sonotrode_radius_m) << " mm sonotrode and " << design.shot_count
            << " shot: is the part really " << size_text << "? If not, its unit is wrong (--unit, read in " << unit_said << ")\n";
    out << "next:  peensim check " << shell_word(scene.string()) << " --render "
        << shell_word(beside_scene(scene.stem().string() + "-check.png").string()) << "\n       peensim run " << shell_word(scene.string())
        << "\n";
    return kExitOk;
}

}  // namespace

int new_scene_job(const NewSceneOptions& options, std::ostream& out, std::ostream& err) {
    return report_errors(err, [&] { return run_new_scene(options, out); });
}

}  // namespace peensim
