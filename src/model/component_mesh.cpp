#include "model/component_mesh.h"

namespace peensim {

TriangleMesh load_component_mesh(const ComponentDesc& desc) {
    MeshFileOptions options;
    options.unit_m = desc.mesh_unit_m;
    options.tessellation.chordal_m = desc.tessellation.chordal_m;
    options.tessellation.angular_rad = desc.tessellation.angular_rad;
    return load_mesh(desc.mesh_path, options);
}

}  // namespace peensim
