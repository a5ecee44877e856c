// A component's mesh as its scene entry says to read it: a mesh file in its `mesh_unit`, or a STEP
// or IGES file at its `tessellation`. The one place that turns a ComponentDesc into load_mesh's
// options, so that the run, `check` and the FEM export see the same triangles (the FEM export maps
// logged facets back onto them).
#pragma once

#include <optional>
#include <string>

#include "geometry/mesh_loader.h"
#include "scene/scene_description.h"

namespace peensim {

// Throws InputError (file = the mesh file, field "mesh") as load_mesh does.
TriangleMesh load_component_mesh(const ComponentDesc& desc);

// The scene's first STEP or IGES mesh, component's or sink's: its file, where the scene gives it
// (its `mesh:` field, or `<--set>`) and that field's name ("components[2].mesh"): what a sweep
// checks this installation can read (geometry/cad_reader.h, require_cad_reading) before it starts
// any run, as compile_model would refuse it in every one.
struct CadMeshUse {
    std::string path;
    SourceLocation where;
    std::string field;
};
std::optional<CadMeshUse> first_cad_mesh(const SceneDescription& scene);

}  // namespace peensim
