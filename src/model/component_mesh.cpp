#include "model/component_mesh.h"

#include "common/cad_file.h"
#include "geometry/cad_reader.h"

namespace peensim {

TriangleMesh load_component_mesh(const ComponentDesc& desc) {
    MeshFileOptions options;
    options.unit_m = desc.mesh_unit_m;
    options.tessellation.chordal_m = desc.tessellation.chordal_m;
    options.tessellation.angular_rad = desc.tessellation.angular_rad;
    return load_mesh(desc.mesh_path, options);
}

void check_cad_meshes_readable(const SceneDescription& scene) {
    const auto check = [](const std::string& path, const SourceLocation& where, const std::string& field) {
        if (!is_cad_file(path)) return;
        try {
            require_cad_reading(path);
        } catch (const InputError& e) {
            throw InputError(where, field, e.problem_at_its_place());
        }
    };
    for (std::size_t i = 0; i < scene.components.size(); ++i)
        check(scene.components[i].mesh_path, scene.components[i].mesh_where, "components[" + std::to_string(i) + "].mesh");
    for (std::size_t k = 0; k < scene.sinks.size(); ++k)
        if (scene.sinks[k].region == SinkRegion::mesh)
            check(scene.sinks[k].mesh_path, scene.sinks[k].mesh_where, "sinks[" + std::to_string(k) + "].mesh");
}

}  // namespace peensim
