// Scenes as Python values: a dict (lists, str, int, float, bool, None) to YAML text the scene
// parser reads, and YAML text back to such a dict. Strings stay strings ("2 mm" keeps its unit);
// a YAML scalar becomes a bool, int or float only when it reads as one entirely.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

namespace peensim::python {

// Block-style YAML of `value` (a dict for a scene, named `name` in messages). Throws
// pybind11::type_error naming the key path of a value that has no YAML form (an object, bytes, a
// NaN), and InputError for maps and lists nested deeper than the command line reads (yaml_load.h).
std::string to_yaml(const pybind11::handle& value, const std::string& name);

// The value of YAML text; throws InputError (named by `name`) for text that is not YAML.
pybind11::object from_yaml(const std::string& text, const std::string& name);

// One value as --set reads it ("60 rpm", 0.002, [0, 0, -9.81], {C0: 0.9}): str as is, the rest as
// YAML flow text. Errors as to_yaml's, naming `file` ("<--set>") and `field` (the path it sets).
std::string override_value(const pybind11::handle& value, const std::string& field, const std::string& file);

}  // namespace peensim::python
