// Counts a mesh file declares, checked against its size before any reader trusts them. A 215-byte
// PLY whose header claims 1e9 vertices made the reader allocate ~12 GB and hang; a binary STL
// whose facet count exceeds its length is as hostile. Each declared element needs at least a
// known number of bytes (binary: its properties' sizes; ASCII: a digit and a separator per
// value), so a count the file cannot hold is refused at once, naming the file and the count.
#pragma once

#include <string>

namespace peensim {

// Throws InputError (file = path, field "mesh") if the file declares more elements than its
// size can hold, or if it is an ASCII STL or an OBJ file that breaks its grammar (at the line:
// geometry/ascii_stl_check.h, geometry/obj_check.h). Other formats pass unchecked.
void precheck_mesh_file(const std::string& path);

}  // namespace peensim
