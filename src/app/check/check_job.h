// `peensim check`: validate a scene completely (parse, load meshes, build the model, check the
// assembly, place the shot) without running it, and print the assembly (every component's world
// bounds, size, triangles, closed or open, clearances to the sonotrode and the chamber, the share
// of its surface the shot can reach, the axes) and the resolved scene with every default filled in.
// Assembly warnings are printed; with `strict` they are errors.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace peensim {

// picture_png: also draw the assembly with the placed shot into this PNG (loads the render module).
int check_job(const std::string& scene_path, const std::vector<std::string>& overrides, bool strict, std::ostream& out, std::ostream& err,
              const std::string& picture_png = "");

// The same, with bad input thrown (InputError: file, line, field) instead of reported, for a caller
// with exceptions of its own (Python); `scene_text`: the scene as YAML in memory, named by scene_path.
// Returns the number of warnings.
std::size_t check_scene(const std::string& scene_path, const std::optional<std::string>& scene_text,
                        const std::vector<std::string>& overrides, bool strict, std::ostream& out, std::ostream& err,
                        const std::string& picture_png = "");

}  // namespace peensim
