// A component's mesh as its scene entry says to read it: a mesh file in its `mesh_unit`, or a STEP
// or IGES file at its `tessellation`. The one place that turns a ComponentDesc into load_mesh's
// options, so that the run, `check` and the FEM export see the same triangles (the FEM export maps
// logged facets back onto them).
#pragma once

#include "geometry/mesh_loader.h"
#include "scene/scene_description.h"

namespace peensim {

// Throws InputError (file = the mesh file, field "mesh") as load_mesh does.
TriangleMesh load_component_mesh(const ComponentDesc& desc);

// Throws the InputError compile_model throws (at the part's `mesh:` field) for the scene's first
// STEP or IGES mesh, component's or sink's, when this installation cannot read STEP and IGES at
// all, without reading any file: a sweep or an optimisation refuses at once what every one of its
// runs would refuse.
void check_cad_meshes_readable(const SceneDescription& scene);

}  // namespace peensim
