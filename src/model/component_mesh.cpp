#include "model/component_mesh.h"

#include "common/cad_file.h"

namespace peensim {

TriangleMesh load_component_mesh(const ComponentDesc& desc) {
    MeshFileOptions options;
    options.unit_m = desc.mesh_unit_m;
    options.tessellation.chordal_m = desc.tessellation.chordal_m;
    options.tessellation.angular_rad = desc.tessellation.angular_rad;
    return load_mesh(desc.mesh_path, options);
}

std::optional<CadMeshUse> first_cad_mesh(const SceneDescription& scene) {
    for (std::size_t i = 0; i < scene.components.size(); ++i)
        if (is_cad_file(scene.components[i].mesh_path))
            return CadMeshUse{scene.components[i].mesh_path, scene.components[i].mesh_where, "components[" + std::to_string(i) + "].mesh"};
    for (std::size_t k = 0; k < scene.sinks.size(); ++k)
        if (scene.sinks[k].region == SinkRegion::mesh && is_cad_file(scene.sinks[k].mesh_path))
            return CadMeshUse{scene.sinks[k].mesh_path, scene.sinks[k].mesh_where, "sinks[" + std::to_string(k) + "].mesh"};
    return std::nullopt;
}

}  // namespace peensim
