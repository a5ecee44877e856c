// Finding and loading a module of peensim's own (libpeensim_render.so, libpeensim_cad.so): parts
// whose libraries cost every process that links them (OSMesa's LLVM: ~50 MB resident;
// OpenCASCADE: ~25 ms of start-up), loaded only by the runs that use them.
#pragma once

#include <string>

namespace peensim {

// Loads `file` from $env_var when it is set (that one only), else the first that opens of: next to
// the executable, one directory up (the tests' place in the build tree), the library search path.
// It stays loaded for the life of the process; returns what its C function `entry_symbol()`
// returns. Throws std::runtime_error saying that `what` needs it, where it looked and why each
// place failed.
const void* load_module_entry(const std::string& file, const char* env_var, const char* entry_symbol, const std::string& what);

}  // namespace peensim
