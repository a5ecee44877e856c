#include "cli/generate_command.h"

#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "common/input_error.h"
#include "common/units.h"
#include "geometry/mesh_checks.h"
#include "geometry/mesh_generators.h"
#include "geometry/stl_writer.h"

namespace peensim {

namespace {

constexpr double kMetresPerMillimetre = 1e-3;  // m/mm: keys ending in -mm, and the STL unit

class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct OptionSpec {
    std::string key;            // without the leading "--"
    std::string default_value;  // "" = required (unless may_be_absent)
    std::string help;
    bool may_be_absent = false;  // no default and not required (an alternative to another key)
};

// The --key value pairs given for one shape, checked against the shape's option list.
class Options {
public:
    Options(const std::vector<OptionSpec>& specs, const std::vector<std::string>& args, std::size_t first) {
        for (const auto& spec : specs) {
            if (!spec.default_value.empty()) values_[spec.key] = spec.default_value;
            known_[spec.key] = true;
        }
        for (std::size_t i = first; i < args.size(); ++i) {
            std::string key = args[i];
            if (key.rfind("--", 0) != 0) throw UsageError("expected --key value, got '" + key + "'");
            key.erase(0, 2);
            std::string value;
            if (const auto eq = key.find('='); eq != std::string::npos) {
                value = key.substr(eq + 1);
                key.resize(eq);
            } else {
                if (i + 1 >= args.size()) throw UsageError("--" + key + " needs a value");
                value = args[++i];
            }
            if (!known_.count(key)) throw UsageError("unknown key --" + key);
            values_[key] = value;
            given_[key] = true;
        }
        for (const auto& spec : specs) {
            if (!values_.count(spec.key) && !spec.may_be_absent) throw UsageError("--" + spec.key + " is required");
        }
    }

    bool given(const std::string& key) const { return given_.count(key) > 0; }
    const std::string& text(const std::string& key) const { return values_.at(key); }

    double number(const std::string& key) const {
        double value = 0.0;
        if (!parse_plain_number(text(key), value)) throw UsageError("--" + key + ": expected a number, got '" + text(key) + "'");
        return value;
    }
    double millimetres(const std::string& key) const { return number(key) * kMetresPerMillimetre; }
    double degrees(const std::string& key) const { return number(key) * std::numbers::pi / 180.0; }
    int count(const std::string& key) const {
        const double value = number(key);
        if (value != std::floor(value) || value < 0 || value > 1e9)
            throw UsageError("--" + key + ": expected a whole number, got '" + text(key) + "'");
        return static_cast<int>(value);
    }
    Vec3 centre() const { return Vec3(millimetres("center-x-mm"), millimetres("center-y-mm"), millimetres("center-z-mm")); }
    Axis axis() const {
        const std::string& a = text("axis");
        if (a == "x") return Axis::x;
        if (a == "y") return Axis::y;
        if (a == "z") return Axis::z;
        throw UsageError("--axis: expected x, y or z, got '" + a + "'");
    }
    bool yes(const std::string& key) const {
        if (text(key) == "yes") return true;
        if (text(key) == "no") return false;
        throw UsageError("--" + key + ": expected yes or no, got '" + text(key) + "'");
    }

private:
    std::map<std::string, std::string> values_;
    std::map<std::string, bool> known_;
    std::map<std::string, bool> given_;
};

struct Shape {
    std::string name;
    std::string summary;
    std::vector<OptionSpec> options;
    std::function<TriangleMesh(const Options&)> build;
};

const std::vector<OptionSpec> kCentre{
    {"center-x-mm", "0", "centre x (mm)"}, {"center-y-mm", "0", "centre y (mm)"}, {"center-z-mm", "0", "centre z (mm)"}};

std::vector<OptionSpec> with_centre(std::vector<OptionSpec> options) {
    options.insert(options.end(), kCentre.begin(), kCentre.end());
    return options;
}

TriangleMesh build_box(const Options& o) {
    BoxSpec spec;
    spec.size_m = Vec3(o.millimetres("size-x-mm"), o.millimetres("size-y-mm"), o.millimetres("size-z-mm"));
    spec.center_m = o.centre();
    spec.divisions = Eigen::Vector3i(o.count("divisions-x"), o.count("divisions-y"), o.count("divisions-z"));
    const std::string& open = o.text("open-face");
    const std::string& facing = o.text("facing");
    if (facing != "outward" && facing != "inward") throw UsageError("--facing: expected outward or inward, got '" + facing + "'");
    const Facing chosen = facing == "inward" ? Facing::inward : Facing::outward;
    if (open == "none") {
        if (chosen == Facing::inward) throw UsageError("--facing inward needs an --open-face (a closed box faces outward)");
        return box(spec);
    }
    const std::map<std::string, BoxFace> faces{{"-x", BoxFace::minus_x}, {"+x", BoxFace::plus_x},  {"-y", BoxFace::minus_y},
                                               {"+y", BoxFace::plus_y},  {"-z", BoxFace::minus_z}, {"+z", BoxFace::plus_z}};
    if (!faces.count(open)) throw UsageError("--open-face: expected none, -x, +x, -y, +y, -z or +z, got '" + open + "'");
    return box_open(spec, faces.at(open), chosen);
}

TriangleMesh build_cylinder(const Options& o) {
    CylinderSpec spec;
    spec.radius_m = o.millimetres("radius-mm");
    spec.height_m = o.millimetres("height-mm");
    spec.segments = o.count("segments");
    spec.axis = o.axis();
    spec.center_m = o.centre();
    spec.capped = o.yes("capped");
    spec.axial_subdivisions = o.count("axial-subdivisions");
    spec.cap_rings = o.count("cap-rings");
    return cylinder(spec);
}

TriangleMesh build_chamber(const Options& o) {
    SteppedChamberSpec spec;
    spec.lower_radius_m = o.millimetres("lower-radius-mm");
    spec.upper_radius_m = o.millimetres("upper-radius-mm");
    spec.bottom_z_m = o.millimetres("bottom-z-mm");
    spec.step_z_m = o.millimetres("step-z-mm");
    spec.lid_z_m = o.millimetres("lid-z-mm");
    spec.segments = o.count("segments");
    spec.lower_layers = o.count("lower-layers");
    spec.upper_layers = o.count("upper-layers");
    spec.step_rings = o.count("step-rings");
    spec.lid_rings = o.count("lid-rings");
    return stepped_tube_chamber(spec);
}

TriangleMesh build_blade(const Options& o) {
    BladeSpec spec;
    spec.chord_m = o.millimetres("chord-mm");
    spec.span_m = o.millimetres("span-mm");
    spec.thickness_m = o.millimetres("thickness-mm");
    spec.twist_rad = o.degrees("twist-deg");
    spec.span_stations = o.count("span-stations");
    spec.chord_points = o.count("chord-points");
    spec.axis = o.axis();
    spec.center_m = o.centre();
    return blade(spec);
}

TriangleMesh build_gear(const Options& o) {
    SpurGearSpec spec;
    spec.module_m = o.millimetres("module-mm");
    spec.teeth = o.count("teeth");
    spec.face_width_m = o.millimetres("face-width-mm");
    spec.pressure_angle_rad = o.degrees("pressure-angle-deg");
    spec.bore_radius_m = o.millimetres("bore-radius-mm");
    spec.addendum_coefficient = o.number("addendum-coefficient");
    spec.dedendum_coefficient = o.number("dedendum-coefficient");
    spec.axis = o.axis();
    spec.center_m = o.centre();
    if (o.given("edge-mm") && o.given("triangles")) throw UsageError("give --triangles or --edge-mm, not both");
    const SpurGearResolution resolution = o.given("edge-mm")
                                              ? gear_resolution_for_edge_length(spec, o.millimetres("edge-mm"))
                                              : gear_resolution_for_triangle_count(spec, static_cast<std::size_t>(o.count("triangles")));
    return spur_gear(spec, resolution);
}

const std::vector<Shape>& shapes() {
    static const std::vector<Shape> list{
        {"box", "axis-aligned box; with --open-face, a box without that face (a chamber)",
         with_centre({{"size-x-mm", "", "edge length along x (mm)"},
                      {"size-y-mm", "", "edge length along y (mm)"},
                      {"size-z-mm", "", "edge length along z (mm)"},
                      {"divisions-x", "1", "quads along x on each face"},
                      {"divisions-y", "1", "quads along y on each face"},
                      {"divisions-z", "1", "quads along z on each face"},
                      {"open-face", "none", "face left out: none, -x, +x, -y, +y, -z, +z"},
                      {"facing", "outward", "normals: outward (a solid) or inward (a chamber, needs --open-face)"}}),
         build_box},
        {"cylinder", "solid circular cylinder (rod, axle, disk), or an open tube with --capped no",
         with_centre({{"radius-mm", "", "radius (mm), vertices on the circle"},
                      {"height-mm", "", "length along the axis (mm)"},
                      {"segments", "64", "polygon sides"},
                      {"axis", "z", "x, y or z"},
                      {"axial-subdivisions", "1", "rings of quads along the axis"},
                      {"cap-rings", "1", "rings per cap (1 = a fan)"},
                      {"capped", "yes", "yes or no"}}),
         build_cylinder},
        {"chamber",
         "two-section cylindrical chamber, z axis, open bottom, normals into the cavity",
         {{"lower-radius-mm", "", "radius of the lower section (mm)"},
          {"upper-radius-mm", "", "radius of the upper section (mm)"},
          {"bottom-z-mm", "", "z of the open bottom rim (mm)"},
          {"step-z-mm", "", "z of the annular step (mm)"},
          {"lid-z-mm", "", "z of the lid (mm)"},
          {"segments", "128", "polygon sides"},
          {"lower-layers", "1", "rings of quads on the lower wall"},
          {"upper-layers", "1", "rings of quads on the upper wall"},
          {"step-rings", "1", "rings on the step"},
          {"lid-rings", "1", "rings on the lid (1 = a fan)"}},
         build_chamber},
        {"gear", "involute spur gear with a bore, extruded along its axis",
         with_centre({{"module-mm", "", "module (mm)"},
                      {"teeth", "", "number of teeth"},
                      {"face-width-mm", "", "width along the axis (mm)"},
                      {"bore-radius-mm", "", "radius of the central bore (mm)"},
                      {"pressure-angle-deg", "20", "pressure angle (deg)"},
                      {"addendum-coefficient", "1", "tip radius = pitch radius + this x module"},
                      {"dedendum-coefficient", "1.25", "root radius = pitch radius - this x module"},
                      {"axis", "y", "x, y or z"},
                      {"triangles", "5000", "target triangle count (the closest resolution is used)"},
                      {"edge-mm", "", "target edge length (mm) instead of --triangles", true}}),
         build_gear},
        {"blade", "thin twisted blade, biconvex section with sharp edges, closed (a part nobody ships: stress tests)",
         with_centre({{"chord-mm", "", "edge to edge (mm)"},
                      {"span-mm", "", "length along the axis (mm)"},
                      {"thickness-mm", "", "at mid-chord (mm); the edges are wedges of 2 atan(2 t / c)"},
                      {"twist-deg", "30", "turn of the section from one end to the other (deg)"},
                      {"span-stations", "40", "sections along the span"},
                      {"chord-points", "40", "points per side along the chord (cosine-spaced)"},
                      {"axis", "x", "the span's axis: x, y or z"}}),
         build_blade},
    };
    return list;
}

void print_usage(std::ostream& out) {
    out << "usage: peensim generate <shape> <output.stl> [--key value ...]\n"
           "Writes a binary STL in millimetres. Shapes:\n";
    for (const Shape& shape : shapes()) {
        out << "\n  " << shape.name << ": " << shape.summary << "\n";
        for (const OptionSpec& o : shape.options) {
            out << "    --" << o.key << "  " << o.help;
            if (!o.default_value.empty())
                out << " [default " << o.default_value << "]";
            else if (!o.may_be_absent)
                out << " [required]";
            out << "\n";
        }
    }
}

std::string millimetre_range(double lo_m, double hi_m) {
    std::ostringstream s;
    s << "[" << lo_m / kMetresPerMillimetre << ", " << hi_m / kMetresPerMillimetre << "]";
    return s.str();
}

void report(std::ostream& out, const std::string& path, const TriangleMesh& mesh) {
    const Bounds box = bounds(mesh);
    out << "wrote " << path << ": " << mesh.triangle_count() << " triangles, " << mesh.vertices.size() << " vertices, ";
    if (is_closed(mesh)) {
        out << "closed, volume " << enclosed_volume(mesh) / std::pow(kMetresPerMillimetre, 3) << " mm3";
    } else {
        out << "open (" << edge_report(mesh).boundary_edges << " boundary edges)";
    }
    out << ", bounds x " << millimetre_range(box.min_m.x(), box.max_m.x()) << " y " << millimetre_range(box.min_m.y(), box.max_m.y())
        << " z " << millimetre_range(box.min_m.z(), box.max_m.z()) << " mm\n";
}

}  // namespace

int run_generate_command(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    if (!args.empty() && (args[0] == "--help" || args[0] == "-h" || args[0] == "help")) {
        print_usage(out);
        return 0;
    }
    TriangleMesh mesh;
    try {
        if (args.size() < 2) throw UsageError("expected a shape and an output file");
        const Shape* shape = nullptr;
        for (const Shape& s : shapes()) {
            if (s.name == args[0]) shape = &s;
        }
        if (shape == nullptr) throw UsageError("unknown shape '" + args[0] + "' (box, cylinder, chamber, gear, blade)");
        if (args[1].rfind("--", 0) == 0) throw UsageError("expected the output file after the shape, got '" + args[1] + "'");
        const Options options(shape->options, args, 2);
        mesh = shape->build(options);
    } catch (const UsageError& e) {
        err << "peensim generate: " << e.what() << "\n(see peensim generate --help)\n";
        return 2;
    } catch (const InputError& e) {
        err << "peensim generate: " << e.problem() << "\n";
        return 2;
    }
    try {
        write_binary_stl(mesh, args[1], kMetresPerMillimetre, args[0]);
    } catch (const InputError& e) {
        err << "peensim generate: " << e.what() << "\n";
        return 1;
    }
    report(out, args[1], mesh);
    return 0;
}

}  // namespace peensim
