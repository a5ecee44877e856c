#include "support/test_scene.h"

#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "geometry/mesh_generators.h"
#include "geometry/stl_writer.h"
#include "scene/scene_parser.h"

namespace fs = std::filesystem;

namespace peensim::testing {

namespace {

constexpr double kMeshUnit_m = 1e-3;  // m per mesh-file unit: the meshes are written in mm

// Shortest text that reads back as the same double.
std::string num(double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}

std::string vec(const Vec3& v) { return "[" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "]"; }

std::string pair(const PairSpec& p, bool surface) {
    std::string s = "{C0: " + num(p.C0) + ", V0: " + num(p.V0_m_per_s) + " m/s";
    if (surface) s += ", mu: " + num(p.mu) + ", f: " + num(p.f);
    return s + "}";
}

// The chamber without the +x wall, when asked for: a hole the closure check must find.
TriangleMesh without_group(const TriangleMesh& mesh, const std::string& group) {
    TriangleMesh out;
    out.vertices = mesh.vertices;
    out.group_names = mesh.group_names;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const auto g = static_cast<std::size_t>(mesh.group_of_triangle[t]);
        if (mesh.group_names[g] == group) continue;
        out.triangles.push_back(mesh.triangles[t]);
        out.source_facet.push_back(static_cast<int>(out.source_facet.size()));
        out.group_of_triangle.push_back(mesh.group_of_triangle[t]);
    }
    return out;
}

TriangleMesh sonotrode_mesh(const TestSceneSpec& s) {
    BoxSpec b;
    b.size_m = Vec3(s.chamber_size_m.x() * s.plate_scale, s.chamber_size_m.y() * s.plate_scale, s.plate_thickness_m);
    b.center_m = Vec3(0.0, 0.0, -0.5 * s.plate_thickness_m);
    b.divisions = s.plate_divisions;
    return box(b);
}

TriangleMesh chamber_mesh(const TestSceneSpec& s) {
    // Walls from the plate's bottom face up to the ceiling, like the shipped rod chamber.
    const double height = s.chamber_size_m.z() + s.plate_thickness_m;
    BoxSpec b;
    b.size_m = Vec3(s.chamber_size_m.x(), s.chamber_size_m.y(), height);
    b.center_m = Vec3(0.0, 0.0, 0.5 * (s.chamber_size_m.z() - s.plate_thickness_m));
    TriangleMesh m = box_open(b, BoxFace::minus_z, Facing::inward);
    return s.chamber_missing_side_wall ? without_group(m, "+x") : m;
}

TriangleMesh part_mesh(const PartSpec& p) {
    switch (p.shape) {
        case PartShape::box:
        case PartShape::plate: {
            BoxSpec b;
            b.size_m = p.size_m;
            b.center_m = p.center_m;
            // A plate gets internal edges on its large faces; a box is one quad per face.
            if (p.shape == PartShape::plate) b.divisions = Eigen::Vector3i(4, 4, 1);
            return box(b);
        }
        case PartShape::cylinder: {
            CylinderSpec c;
            c.radius_m = p.radius_m;
            c.height_m = p.length_m;
            c.segments = p.segments;
            c.axis = p.axis;
            c.center_m = p.center_m;
            return cylinder(c);
        }
    }
    throw std::logic_error("unknown part shape");
}

std::string make_temporary_directory() {
    std::string pattern = (fs::temp_directory_path() / "peensim-test-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create a temporary directory from " + pattern);
    return pattern;
}

}  // namespace

std::string scene_yaml(const TestSceneSpec& s) {
    std::ostringstream y;
    y << "name: generated test scene\n"
      << "process:\n"
      << "  duration: " << num(s.duration_s) << " s\n"
      << "  gravity: " << vec(s.gravity_m_per_s2) << "\n"
      << "  seed: " << s.seed << "\n"
      << "accuracy:\n"
      << "  travel_fraction: " << num(s.travel_fraction) << "\n"
      << "  scheme: " << s.scheme << "\n";
    if (s.soft) y << "  soft_steps_per_contact: " << num(s.soft->steps_per_contact) << "\n";
    y << "shot:\n"
      << "  count: " << s.shot_count << "\n";
    if (s.shot_sizes.empty()) {
        y << "  diameter: " << num(s.shot_diameter_m) << " m\n";
    } else {
        y << "  fractions_by: count\n  sizes:\n";
        for (const auto& [d, f] : s.shot_sizes) y << "    - {diameter: " << num(d) << " m, fraction: " << num(f) << "}\n";
    }
    if (s.soft)
        y << "  material: shot_steel\n";
    else
        y << "  density: " << num(s.shot_density_kg_per_m3) << " kg/m3\n";
    if (s.initial_velocity_m_per_s) y << "  initial_velocity: " << vec(*s.initial_velocity_m_per_s) << "\n";
    if (s.initial_speed_m_per_s) y << "  initial_speed: " << num(*s.initial_speed_m_per_s) << " m/s\n";
    if (s.soft) {
        const SoftSpec& k = *s.soft;
        const std::string elastic = ", youngs_modulus: " + num(k.youngs_modulus_pa) + " Pa, poisson_ratio: " + num(k.poisson_ratio) + "}";
        const auto hm = [&](double e, double f) {
            if (k.linear)
                return "{law: linear-spring-dashpot, e: " + num(e) + ", f: " + num(f) +
                       ", characteristic_speed: " + num(k.characteristic_speed_m_per_s) + " m/s}";
            return "{law: hertz-mindlin, e: " + num(e) + ", f: " + num(f) + ", plastic_speed: " + num(k.V0_m_per_s) + " m/s}";
        };
        y << "materials:\n"
          << "  shot_steel: {density: " << num(s.shot_density_kg_per_m3) << " kg/m3" << elastic << "\n"
          << "  titanium: {density: 4430 kg/m3" << elastic << "\n"
          << "  steel: {density: 7800 kg/m3" << elastic << "\n"
          << "  copper: {density: 8960 kg/m3, yield_stress: 70 MPa" << elastic << "\n"
          << "contacts:\n"
          << "  shot-shot: " << hm(k.e_shot_shot, k.f_shot_shot) << "\n"
          << "  shot-titanium: " << hm(k.e_sonotrode, k.f_sonotrode) << "\n"
          << "  shot-steel: " << hm(k.e_chamber, k.f_chamber) << "\n"
          << "  shot-copper: " << hm(k.e_part, k.f_part) << "\n";
    } else {
        y << "materials:\n"
          << "  titanium: {density: 4430 kg/m3}\n"
          << "  steel: {density: 7800 kg/m3}\n"
          << "  copper: {density: 8960 kg/m3, yield_stress: 70 MPa}\n"
          << "contacts:\n"
          << "  shot-shot: " << pair(s.shot_shot, false) << "\n"
          << "  shot-titanium: " << pair(s.sonotrode, true) << "\n"
          << "  shot-steel: " << pair(s.chamber, true) << "\n"
          << "  shot-copper: " << pair(s.part_pair, true) << "\n";
    }
    y << "components:\n"
      << "  - name: sonotrode\n"
      << "    role: sonotrode\n"
      << "    mesh: sonotrode.stl\n"
      << "    mesh_unit: mm\n"
      << "    material: titanium\n"
      << "    vibration: {amplitude: " << num(s.amplitude_m) << " m, frequency: " << num(s.frequency_hz)
      << " Hz, phase: " << num(s.phase_rad) << " rad, axis: [0, 0, 1]}\n"
      << "  - name: chamber\n"
      << "    role: chamber\n"
      << "    mesh: chamber.stl\n"
      << "    mesh_unit: mm\n"
      << "    material: steel\n";
    if (s.part) {
        y << "  - name: part\n"
          << "    role: part\n"
          << "    mesh: part.stl\n"
          << "    mesh_unit: mm\n"
          << "    material: copper\n";
        if (s.part->speed_rad_per_s)
            y << "    motion: {type: rotating, axis_point: " << vec(s.part->axis_point_m)
              << ", axis_direction: " << vec(s.part->axis_direction) << ", speed: " << num(*s.part->speed_rad_per_s) << " rad/s}\n";
    }
    if (!s.log.empty()) {
        y << "output:\n  log: [";
        for (std::size_t i = 0; i < s.log.size(); ++i) y << (i ? ", " : "") << s.log[i];
        y << "]\n";
    }
    return y.str();
}

TestScene::TestScene(const TestSceneSpec& spec) : spec_(spec), directory_(make_temporary_directory()) {
    const fs::path dir(directory_);
    write_binary_stl(sonotrode_mesh(spec), (dir / "sonotrode.stl").string(), kMeshUnit_m, "sonotrode");
    write_binary_stl(chamber_mesh(spec), (dir / "chamber.stl").string(), kMeshUnit_m, "chamber");
    if (spec.part) write_binary_stl(part_mesh(*spec.part), (dir / "part.stl").string(), kMeshUnit_m, "part");
    yaml_ = scene_yaml(spec);
    scene_path_ = (dir / "scene.yaml").string();
    std::ofstream(scene_path_) << yaml_;
}

TestScene::~TestScene() {
    std::error_code ignored;
    fs::remove_all(directory_, ignored);
}

std::shared_ptr<const Model> TestScene::compile(const std::vector<std::string>& overrides) const {
    return compile_model(parse_scene_text(yaml_, scene_path_, overrides));
}

void set_shot(SimulationState& state, std::size_t i, const Vec3& position_m, const Vec3& velocity_m_per_s) {
    state.shots.set_position(i, position_m);
    state.shots.set_velocity(i, velocity_m_per_s);
    state.fastest_shot_m_per_s = std::max(state.fastest_shot_m_per_s, velocity_m_per_s.norm());
}

std::string TestScene::make_subdirectory(const std::string& name) const {
    const fs::path p = fs::path(directory_) / name;
    fs::remove_all(p);
    fs::create_directories(p);
    return p.string();
}

TestSceneSpec thrown_shot_scene(int shot_count, double duration_s) {
    TestSceneSpec spec;
    spec.shot_count = shot_count;
    spec.initial_speed_m_per_s = 1.0;
    spec.amplitude_m = 25e-6;
    spec.duration_s = duration_s;
    return spec;
}

PartSpec turning_plate_part(double omega_rad_per_s) {
    PartSpec part;
    part.shape = PartShape::plate;
    part.size_m = Vec3(10e-3, 6e-3, 2e-3);
    part.center_m = Vec3(0.0, 0.0, 10e-3);
    part.speed_rad_per_s = omega_rad_per_s;
    part.axis_point_m = part.center_m;
    part.axis_direction = Vec3::UnitY();
    return part;
}

TestSceneSpec small_rod_scene(const std::string& scheme, double duration_s) {
    TestSceneSpec spec = thrown_shot_scene(64, duration_s);
    spec.scheme = scheme;
    PartSpec rod;
    rod.shape = PartShape::cylinder;
    rod.radius_m = 3e-3;
    rod.length_m = 16e-3;
    rod.center_m = Vec3(0.0, 0.0, 8e-3);
    spec.part = rod;
    return spec;
}

}  // namespace peensim::testing
