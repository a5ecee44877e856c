// A Wavefront OBJ read line by line before the reader sees it: the reader (assimp) takes the
// number at the front of a word ("2x" reads as 2: a silently wrong part), reads a word that is
// no number as a vertex of fewer coordinates, and then reports "vertex index out of range" with
// no line. This check names the first line whose numbers or face corners are broken.
//
// Checked, at their lines: `v` (3 to 7 finite numbers: x y z [w] or x y z r g b [a]), `vn` (3
// numbers, "nan" too: the reader uses no normal), `vt` (1 to 3), and the corners of `f`, `l` and
// `p` (v, v/vt, v//vn or v/vt/vn: whole non-zero integers, a negative one counting back from the
// vertex before it; a face of 3 corners at least, a line of 2). A corner's vertex past the file's
// last one is named at its line. Other keywords (g, o, s, usemtl, mtllib, ...) and comments pass;
// a line ending in '\' goes on on the next.
#pragma once

#include <istream>
#include <string>

namespace peensim {

// Throws InputError (file = path, line, column, field "mesh") at the first broken line of `in`.
void check_obj(const std::string& path, std::istream& in);

}  // namespace peensim
