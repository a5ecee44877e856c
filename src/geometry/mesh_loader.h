// Reads a mesh file (STL ASCII or binary, OBJ, PLY; anything assimp reads) into a TriangleMesh
// in metres, keeping the link from every triangle back to its facet in the file.
//
// Facet numbering (TriangleMesh::source_facet): the polygons of the file counted from 0, in
// the order assimp lists them: mesh after mesh of the scene, face after face within a mesh.
// For STL that is the facet order of the file; for OBJ it is the order of the `f` lines
// (assimp makes one mesh per run of a group, in file order); for PLY the order of the face
// element. Points and lines are not polygons and are not counted. A polygon with n > 3
// corners is split into a fan of n - 2 triangles that all carry the polygon's number.
// Degenerate triangles (zero area after welding) are dropped without renumbering the others.
//
// Vertices are welded by exact position (as read, before scaling). File normals are ignored;
// a triangle's normal is its winding (see mesh_checks.h). Groups: one per distinct name of an
// assimp mesh (STL "solid <name>", OBJ "g <name>"), or of the node holding it if the mesh is
// unnamed; "" if neither has a name. Node transforms are applied (identity for STL/OBJ/PLY).
//
// STEP and IGES files (common/cad_file.h: by the extension) are read by geometry/cad_reader.h
// instead, under the same contract: tessellated with the options' tolerances, in the length unit
// the file states (unit_m does not apply to them), one facet per B-rep face, one group per solid.
#pragma once

#include <string>

#include "geometry/cad_reader.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

struct MeshFileOptions {
    double unit_m = 1.0;        // m per length unit of a mesh file (1e-3 for a file in mm); not for STEP/IGES
    Tessellation tessellation;  // STEP/IGES only: how their exact surfaces become triangles
};

// Throws InputError (file = path, field "mesh") if the file is missing, cannot be parsed,
// holds a non-finite coordinate, or holds no triangle of non-zero area.
TriangleMesh load_mesh(const std::string& path, const MeshFileOptions& options);

// unit_m: metres per length unit of the file (1e-3 for a file in mm); a STEP/IGES file is
// tessellated at the default tolerances (Tessellation{}) in its own unit.
TriangleMesh load_mesh(const std::string& path, double unit_m);

}  // namespace peensim
