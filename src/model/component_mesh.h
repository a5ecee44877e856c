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

}  // namespace peensim
