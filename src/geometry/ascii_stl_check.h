// An ASCII STL read line by line against its grammar before the reader sees it. The reader
// (assimp) takes the number at the front of a word ("2x" reads as 2: a silently wrong part) and
// names no line when it gives up ("Cannot parse string ... as a real number"); this check names
// the first line that breaks the grammar and what it expected there.
//
// Grammar, keywords in any case, words apart by blanks, blank lines allowed:
//   solid [name]
//     facet [normal X Y Z]
//       outer loop
//         vertex X Y Z      (three of them)
//       endloop
//     endfacet
//   endsolid [name]
// (solids may follow one another). Numbers are whole decimal words; a vertex's finite (a normal
// may be "nan": writers give one to a degenerate facet, and the reader ignores normals).
#pragma once

#include <istream>
#include <string>

namespace peensim {

// Throws InputError (file = path, the line and column, field "mesh") at the first line of `in`
// (an ASCII STL from its first byte) that breaks the grammar, or at its end if a solid is left
// open.
void check_ascii_stl(const std::string& path, std::istream& in);

}  // namespace peensim
