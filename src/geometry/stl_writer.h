// Writers of STL files. Both write the triangles in file units (metres / unit_m, e.g.
// unit_m = 1e-3 for millimetres) with facet normals computed from the winding, and both go
// through "<path>.partial" renamed into place, so a crash never leaves a half-written mesh.
// Failing to write throws InputError (field "output") naming the path.
#pragma once

#include <string>

#include "geometry/triangle_mesh.h"

namespace peensim {

// Binary STL: 80-byte header (never starting with "solid", which some readers take for ASCII;
// it records the unit and solid_name), little-endian float32 data. Facet i of the file is
// triangle i of the mesh. Groups are not stored (binary STL has one solid).
void write_binary_stl(const TriangleMesh& mesh, const std::string& path, double unit_m = 1e-3, const std::string& solid_name = "");

// ASCII STL, one "solid <group name>" block per group of the mesh (a single solid named
// solid_name if the mesh has no groups). Triangles are written group by group, in mesh order
// within each group, so the file's facet order equals the mesh order only when the groups are
// contiguous. Coordinates with 9 significant digits (exact for float32). Meant for tests.
void write_ascii_stl(const TriangleMesh& mesh, const std::string& path, double unit_m = 1e-3, const std::string& solid_name = "");

}  // namespace peensim
