// Scene file (YAML) -> SceneDescription: every value in SI, every default filled in, every
// reference checked. The format is described by scene/schema.h (`peensim schema` prints it).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/scene_description.h"

namespace peensim {

// Reads and checks a scene file. `overrides` are --set strings "path=value" applied before the
// checks (see scene/overrides.h). Throws InputError with file, line, field and what was expected.
SceneDescription parse_scene_file(const std::string& path, const std::vector<std::string>& overrides = {});

// The same for text already in memory; `virtual_path` names it in messages, and relative mesh paths
// are resolved against its directory.
SceneDescription parse_scene_text(const std::string& yaml_text, const std::string& virtual_path,
                                  const std::vector<std::string>& overrides = {});

// The text when given (a scene in memory: Python's dict), else the file.
inline SceneDescription parse_scene(const std::string& path, const std::optional<std::string>& text,
                                    const std::vector<std::string>& overrides = {}) {
    return text ? parse_scene_text(*text, path, overrides) : parse_scene_file(path, overrides);
}

}  // namespace peensim
