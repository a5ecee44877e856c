// What the user hands peensim that becomes a file: a name joined to an output directory (export-fem
// --name) must stay inside that directory, and a file path for an extra output (--plot, --json,
// --csv) must go into a directory that already exists. Users found `--name ../../x` writing the deck
// outside -o, and `--plot /nonexistent/dir/p.png` creating /nonexistent. Both refuse with an
// InputError naming the option and what was expected (exit 2), before any work is done.
#pragma once

#include <cstddef>
#include <string>

namespace peensim {

// The longest name accepted: the file names made from it (name + ".inp", "_points.csv") stay
// within the 255 bytes a file name may have on Linux file systems.
inline constexpr std::size_t kMaxOutputNameBytes = 200;

// Whether `name` can be one file name inside an output directory: non-empty, at most
// kMaxOutputNameBytes, of letters, digits, '.', '-' and '_' only, neither "." nor "..". A sweep's
// variant names (its runs' directories) follow the same rule.
bool is_output_name(const std::string& name);

// `name` is used as one file name (or its stem) inside an output directory: it must be non-empty,
// at most kMaxOutputNameBytes, of letters, digits, '.', '-' and '_' only (so no path separator,
// no absolute path, nothing the shell or the FEM solver's job name would split), and neither "."
// nor "..". Throws InputError({option}, ...) otherwise.
void check_output_name(const std::string& option, const std::string& name);

// `path` names an output file: its directory ("." when it has none) must exist and be a
// directory; peensim does not create directories the user did not ask for. Throws InputError.
void check_output_file_directory(const std::string& option, const std::string& path);

}  // namespace peensim
