// Every YAML text peensim reads (scene files, --set values, sweep files, the Python API's dicts and
// texts) is loaded here, under one nesting limit: maps and lists nested deeper than
// kMaxYamlNesting levels are refused before they are built, with one message, wherever they come
// from. yaml-cpp's own guard (about 500 levels) only protects its parser: a tree deeper than a
// scene can use is still slow to walk, and a Python value has no parser in front of it.
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

namespace peensim {

// The deepest nesting of maps and lists any input may have (levels; a scene file needs at most 6).
inline constexpr int kMaxYamlNesting = 64;

// "maps and lists nested deeper than 64 levels; expected at most 64 (a scene needs fewer than 10)".
std::string yaml_nesting_problem();

// YAML::Load under the nesting limit: beyond it, throws YAML::ParserException (its mark: where the
// level too many opens) with yaml_nesting_problem() as its message. Other errors as YAML::Load's.
YAML::Node load_yaml(const std::string& text);

// The same for a file (YAML::BadFile if it cannot be read).
YAML::Node load_yaml_file(const std::string& path);

}  // namespace peensim
