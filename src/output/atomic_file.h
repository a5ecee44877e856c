// Whole-file outputs (summary.json, checkpoints) written so that a crash, a kill or a power
// cut leaves either the old file or the new one, never a half-written mix.
#pragma once

#include <string>
#include <string_view>

namespace peensim {

// Writes `content` to `path.tmp`, fsyncs it, renames it over `path` and fsyncs the directory.
// Throws std::runtime_error naming the path and the errno text on any failure; the `.tmp`
// file is removed then, and `path` keeps its previous content.
void write_file_atomically(const std::string& path, std::string_view content);

}  // namespace peensim
