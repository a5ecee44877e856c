// `peensim generate <shape> <output.stl> [--key value ...]`: writes a generated mesh (box,
// cylinder, stepped chamber, spur gear) as a binary STL in millimetres. Lengths are given in
// millimetres by keys that say so (--radius-mm 5), angles in degrees (--pressure-angle-deg 20).
// `peensim generate --help` lists the shapes and their keys.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace peensim {

// args: everything after "generate". Prints what was written to `out`, problems to `err`.
// Returns 0 on success, 2 for bad arguments or impossible shape parameters, 1 if the file
// cannot be written.
int run_generate_command(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace peensim
