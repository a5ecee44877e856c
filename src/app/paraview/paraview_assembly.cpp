#include "app/paraview/paraview_assembly.h"

#include <filesystem>
#include <vector>

#include "output/vtk_collection.h"
#include "output/vtp_writer.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

const char* motion_name(Kinematics::Kind k) {
    switch (k) {
        case Kinematics::Kind::fixed: return "fixed";
        case Kinematics::Kind::vibrating: return "vibrating";
        case Kinematics::Kind::rotating: return "rotating";
    }
    return "fixed";
}

std::vector<double> numbers(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

// The block's field data (see the header).
std::vector<FieldValue> block_field_data(const Component& c) {
    const Kinematics& k = c.kinematics;
    std::vector<double> rotation;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) rotation.push_back(k.rest.rotation(row, col));
    std::vector<FieldValue> f = {{"component", c.name},
                                 {"role_name", std::string(role_name(c.role))},
                                 {"motion", std::string(motion_name(k.kind))},
                                 {"pose_rotation", rotation},
                                 {"pose_translation_m", numbers(k.rest.translation)}};
    if (k.kind == Kinematics::Kind::vibrating) {
        f.push_back({"vibration_axis", numbers(k.axis)});
        f.push_back({"amplitude_m", std::vector<double>{k.amplitude_m}});
        f.push_back({"frequency_hz", std::vector<double>{k.frequency_hz}});
        f.push_back({"phase_rad", std::vector<double>{k.phase_rad}});
    }
    if (k.kind == Kinematics::Kind::rotating) {
        f.push_back({"axis_point_m", numbers(k.axis_point_m)});
        f.push_back({"axis_direction", numbers(k.axis_direction)});
        f.push_back({"angular_speed_rad_per_s", std::vector<double>{k.omega_rad_per_s}});
    }
    return f;
}

void write_block(const Component& c, const std::string& path) {
    const TriangleMesh& mesh = *c.mesh;
    const std::uint64_t n = mesh.triangle_count();
    PolyDataLayout layout{mesh.vertices.size(), PolyDataLayout::Cells::triangles, n, {}, {{"role", VtkType::int32, 1}},
                          block_field_data(c)};
    PolyDataWriter out(path, std::move(layout));
    const Pose at_start = c.kinematics.pose(SimTime{});
    for (const Vec3& v : mesh.vertices) out.add_point(at_start.to_world(v));
    out.add_triangles(mesh.triangles);
    const auto role = static_cast<std::int32_t>(c.role);
    for (std::uint64_t t = 0; t < n; ++t) out.add(role);
    out.finish();
}

}  // namespace

void write_paraview_assembly(const Model& model, const std::string& run_dir) {
    const fs::path dir = fs::path(run_dir) / kParaviewDirName;
    fs::create_directories(dir / "assembly");
    std::vector<NamedBlock> blocks;
    for (const Component& c : model.components) {
        const std::string file = "assembly/" + c.name + ".vtp";
        write_block(c, (dir / file).string());
        blocks.push_back({c.name, file});
    }
    write_vtm((dir / kAssemblyFileName).string(), blocks);
}

}  // namespace peensim
