// What the command's own YAML files (a sweep file, a study file) share with their messages: where
// a node is, and a node as the text `--set` reads.
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

#include "common/input_error.h"

namespace peensim {

// The file, line and column (1-based) of a node.
inline SourceLocation yaml_location(const std::string& file, const YAML::Node& n) { return {file, n.Mark().line + 1, n.Mark().column + 1}; }

// A scalar as written, a list or map in YAML's flow form.
inline std::string yaml_text(const YAML::Node& n) {
    if (n.IsScalar()) return n.Scalar();
    YAML::Emitter e;
    e << YAML::Flow << n;
    return e.c_str();
}

}  // namespace peensim
