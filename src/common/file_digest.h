// A file's bytes as a short text, for the scene's hash (scene/resolved_writer.h): a run's mesh
// re-exported to the same path is another simulation, and a byte-identical copy under another path
// is the same one. The hash followed the path before, so `peensim run --resume` and a sweep's
// finished runs took a mesh changed in place for the one they had run.
#pragma once

#include <string>

namespace peensim {

// "fnv1a64 <16 hex digits>, <size> B" of the file's bytes; "unreadable <path>" when it cannot be
// read (the scene then fails where it loads the mesh, with its own message). Each file is read once
// per process while its size and modification time stay the same.
std::string file_digest_text(const std::string& path);

}  // namespace peensim
