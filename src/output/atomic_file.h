// Whole-file outputs (summary.json, checkpoints) written so that a crash, a kill or a power
// cut leaves either the old file or the new one, never a half-written mix.
#pragma once

#include <string>
#include <string_view>

namespace peensim {

// How far an atomic write is safe: `power_cut` fsyncs the file and its directory (results,
// checkpoints); `process_crash` only renames (a crash or kill still never leaves a half file, a
// power cut may lose the new one: for outputs cheap to make again, like animation frames, where
// an fsync each would cost more than making them).
enum class Durability { power_cut, process_crash };

// Writes `content` to `path.tmp`, renames it over `path` (fsyncing as `durability` says).
// Throws std::runtime_error naming the path and the errno text on any failure; the `.tmp`
// file is removed then, and `path` keeps its previous content.
void write_file_atomically(const std::string& path, std::string_view content, Durability durability = Durability::power_cut);

}  // namespace peensim
