// Components: names, roles, mesh files, placement, vibration (sonotrode) and motion (parts).
#include <cmath>
#include <system_error>

#include "common/cad_file.h"
#include "scene/scene_sections.h"

namespace peensim {
namespace {

// How far M M^T may be from the identity for `rotation.matrix` to count as a rotation (-); loose
// enough for matrices typed with 16 digits, tight enough to catch a scaled or sheared matrix.
constexpr double rotation_matrix_tolerance = 1e-9;

ComponentRole role_from(const std::string& word) {
    if (word == "sonotrode") return ComponentRole::sonotrode;
    if (word == "chamber") return ComponentRole::chamber;
    if (word == "part") return ComponentRole::part;
    if (word == "almen") return ComponentRole::almen;
    return ComponentRole::fixture;
}

Mat3 read_rotation(const Cursor& c) {
    if (!c.is_map()) return Mat3::Identity();
    const Cursor axis = c.child("axis");
    const Cursor angle = c.child("angle");
    const Cursor euler = c.child("euler_xyz");
    const Cursor matrix = c.child("matrix");
    const int forms = int(axis.present() || angle.present()) + int(euler.present()) + int(matrix.present());
    if (forms > 1) fail(c, "expected one of {axis, angle}, {euler_xyz} or {matrix}, got several");
    if (axis.present() || angle.present()) {
        if (!axis.present()) fail(axis, "missing required key 'axis' (rotation.angle needs an axis)");
        if (!angle.present()) fail(angle, "missing required key 'angle' (rotation.axis needs an angle)");
        return Eigen::AngleAxisd(read_quantity(angle), *read_optional_direction(axis)).toRotationMatrix();
    }
    if (euler.present()) {
        const Vec3 a = read_vector(euler);  // rad
        // Intrinsic X, then the new Y, then the newest Z: R = Rx(a) Ry(b) Rz(c).
        return (Eigen::AngleAxisd(a.x(), Vec3::UnitX()) * Eigen::AngleAxisd(a.y(), Vec3::UnitY()) * Eigen::AngleAxisd(a.z(), Vec3::UnitZ()))
            .toRotationMatrix();
    }
    if (matrix.present()) {
        const Mat3 m = read_matrix(matrix);
        const double off = (m * m.transpose() - Mat3::Identity()).cwiseAbs().maxCoeff();
        if (!(off <= rotation_matrix_tolerance) || !(m.determinant() > 0.0))
            fail(matrix, "expected a rotation matrix (orthonormal rows, determinant +1)");
        return m;
    }
    return Mat3::Identity();
}

std::optional<VibrationDesc> read_vibration(const Cursor& c, const ComponentDesc& k) {
    if (k.role != ComponentRole::sonotrode) {
        if (c.present()) fail(c, "vibration is only for the sonotrode; '" + k.name + "' is not one (forbidden here)");
        return std::nullopt;
    }
    if (!c.present()) fail(c, "missing required key 'vibration' (the sonotrode needs amplitude and frequency)");
    VibrationDesc v;
    v.amplitude_m = read_quantity(c.child("amplitude"));
    v.frequency_hz = read_quantity(c.child("frequency"));
    if (v.amplitude_m > 0.0 && !(v.frequency_hz > 0.0)) fail(c.child("frequency"), "expected a frequency > 0 Hz when the amplitude is > 0");
    v.phase_rad = read_quantity(c.child("phase"));
    v.axis = read_optional_direction(c.child("axis"));
    v.where = location_of(c);
    return v;
}

std::optional<RotationDesc> read_motion(const Cursor& c, const ComponentDesc& k) {
    if (!c.is_map()) return std::nullopt;  // absent, or the word `static`
    if (read_choice(c.child("type")) == "static") {
        for (std::string_view key : {"axis_point", "axis_direction", "speed"})
            if (c.child(key).present()) fail(c.child(key), "a static motion takes no '" + std::string(key) + "'");
        return std::nullopt;
    }
    if (k.role != ComponentRole::part) fail(c, "a rotating motion is only for role part; '" + k.name + "' is not a part");
    RotationDesc r;
    // No default: left at the world origin, a gear 42 mm up orbited through the sonotrode and a wall.
    const Cursor point = c.child("axis_point");
    if (!point.present()) fail(point, "missing required key 'axis_point' (a rotating motion needs a point on its axis, world frame)");
    r.axis_point_m = read_vector(point);
    const Cursor direction = c.child("axis_direction");
    if (!direction.present()) fail(direction, "missing required key 'axis_direction' (a rotating motion needs it)");
    r.axis_direction = *read_optional_direction(direction);
    const Cursor speed = c.child("speed");
    if (!speed.present()) fail(speed, "missing required key 'speed' (a rotating motion needs it)");
    r.speed_rad_per_s = read_quantity(speed);
    r.where = location_of(c);
    return r;
}

std::optional<AlmenDesc> read_almen(const Cursor& c, const ComponentDesc& k) {
    if (k.role != ComponentRole::almen) {
        if (c.present()) fail(c, "almen is only for role almen; '" + k.name + "' is not an Almen strip (forbidden here)");
        return std::nullopt;
    }
    AlmenDesc a;
    if (const auto normal = read_optional_direction(c.child("face_normal"))) a.face_normal = *normal;
    const Cursor height = c.child("saturation_arc_height");
    const Cursor dose = c.child("dose_constant");
    if (height.present() != dose.present())
        fail(height.present() ? dose : height, std::string("missing required key '") +
                                                   (height.present() ? "dose_constant" : "saturation_arc_height") +
                                                   "' (the arc-height calibration needs both saturation_arc_height and dose_constant)");
    if (height.present()) {
        a.saturation_arc_height_m = read_quantity(height);
        a.dose_constant_J_per_m2 = read_quantity(dose);
    }
    const Cursor model = c.child("calibration");
    if (model.present()) {
        if (height.present())
            fail(model,
                 "give either calibration (the predictive model) or saturation_arc_height and dose_constant (the dose model), not both");
        AlmenCalibrationDesc m;
        m.saturation_arc_height_m = read_quantity(model.child("saturation_arc_height"));
        m.time_constant_s = read_quantity(model.child("time_constant"));
        m.shape = read_quantity(model.child("shape"));
        m.dent_size_m = read_quantity(model.child("dent_size"));
        m.covering_rate_per_s = read_quantity(model.child("covering_rate"));
        if (model.child("strip").present()) m.strip = read_choice(model.child("strip"));
        a.calibration = m;
    }
    a.where = location_of(c);
    return a;
}

// A STEP or IGES file states its length unit and is read in it (a CAD user expects the file to win):
// a mesh_unit beside it would be ignored or contradict it, so it is refused; tessellation is for
// those files only (a mesh file is already triangles).
void read_mesh_unit_and_tessellation(const Cursor& c, ComponentDesc& k) {
    const Cursor unit = c.child("mesh_unit");
    const Cursor tessellation = c.child("tessellation");
    if (!is_cad_file(k.mesh_path)) {
        if (tessellation.present())
            fail(tessellation, "tessellation is only for STEP and IGES files; '" + k.mesh_path + "' is a mesh file, already triangles");
        k.mesh_unit_m = parse_quantity("1 " + read_choice(unit), Dimension::length);
        return;
    }
    if (unit.present())
        fail(unit, "mesh_unit does not apply to a STEP or IGES file: '" + k.mesh_path +
                       "' states its own length unit, which is used; remove mesh_unit");
    k.mesh_unit_m = 1.0;  // the reader returns metres
    k.tessellation.chordal_m = read_quantity(tessellation.child("chordal"));
    k.tessellation.angular_rad = read_quantity(tessellation.child("angular"));
}

ComponentDesc read_component(const Cursor& c, const std::filesystem::path& scene_dir, const std::vector<MaterialDesc>& materials) {
    ComponentDesc k;
    k.name = read_text(c.child("name"));
    if (!is_valid_name(k.name)) fail(c.child("name"), "invalid name '" + k.name + "'; names use only A-Z a-z 0-9 _ -");
    k.role = role_from(read_choice(c.child("role")));
    k.mesh_path = resolve_mesh(c.child("mesh"), scene_dir);
    k.mesh_where = location_of(c.child("mesh"));
    read_mesh_unit_and_tessellation(c, k);
    k.translation_m = read_vector(c.child("translation"));
    k.rotation = read_rotation(c.child("rotation"));
    k.material = read_text(c.child("material"));
    if (!k.material.empty() && find_material(materials, k.material) == nullptr)
        fail(c.child("material"), "unknown material '" + k.material + "'; expected one of the materials: " + material_names(materials));
    k.vibration = read_vibration(c.child("vibration"), k);
    k.rotation_motion = read_motion(c.child("motion"), k);
    k.regions = read_regions(c.child("regions"));
    k.almen = read_almen(c.child("almen"), k);
    k.where = location_of(c);
    return k;
}

}  // namespace

std::string resolve_mesh(const Cursor& mesh, const std::filesystem::path& scene_dir) {
    namespace fs = std::filesystem;
    const std::string given = read_text(mesh);
    fs::path p(given);
    if (p.is_relative()) p = scene_dir / p;
    p = p.lexically_normal();
    std::error_code ec;
    const fs::file_status st = fs::status(p, ec);
    if (!fs::exists(st))
        fail(mesh, "mesh file not found: '" + p.string() +
                       "' (expected an existing file; relative paths are "
                       "resolved against the scene file's directory '" +
                       scene_dir.string() + "')");
    if (!fs::is_regular_file(st)) fail(mesh, "'" + p.string() + "' is not a regular file (expected a mesh file)");
    return p.string();
}

std::vector<ComponentDesc> read_components(const Cursor& c, const std::filesystem::path& scene_dir,
                                           const std::vector<MaterialDesc>& materials) {
    std::vector<ComponentDesc> out;
    for (std::size_t i = 0; i < c.size(); ++i) {
        const Cursor item = c.item(i);
        ComponentDesc k = read_component(item, scene_dir, materials);
        for (std::size_t j = 0; j < out.size(); ++j)
            if (out[j].name == k.name)
                fail(item.child("name"),
                     "duplicate component name '" + k.name + "' (also components[" + std::to_string(j) + "]); names must be unique");
        out.push_back(std::move(k));
    }
    return out;
}

}  // namespace peensim
