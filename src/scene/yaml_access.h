// Located, schema-driven reads of a scene's YAML tree. A Cursor is one node together with its
// schema path (for defaults and ranges), its field path (for messages) and its place in the file;
// every read either returns an SI value or throws an InputError pointing at that place.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "common/input_error.h"
#include "common/vec.h"
#include "scene/schema.h"

namespace peensim {

// A field set (or a map created) by a --set override; errors inside it point at the override.
struct OverrideOrigin {
    std::string field_path;  // canonical, with list indices: "components[1].motion.speed"
    std::string text;        // the override as given: "components[gear].motion.speed=60 rpm"
};

// A quantity with a dimension written as a plain number (read in SI): with units given elsewhere
// in the scene, most likely a forgotten unit ("amplitude: 25" is 25 m).
struct PlainQuantity {
    SourceLocation where;
    std::string field;
    std::string text;
    Dimension dimension = Dimension::dimensionless;
};

struct SceneContext {
    std::string file;                       // the scene file as given (for messages)
    std::vector<OverrideOrigin> overrides;  // filled by apply_overrides
    // Noted while reading (the cursors see the context as const).
    mutable std::vector<PlainQuantity> plain_quantities;
    mutable bool units_given = false;    // some quantity was written with a unit
    mutable bool units_in_file = false;  // ... in the file itself (not in a --set override)
};

// A direction whose length is already 1 within this tolerance is kept as written instead of being
// divided by its norm again: normalising is not idempotent in floating point, and the resolved
// scene must read back to bit-identical values.
inline constexpr double unit_length_tolerance = 1e-14;

// The file name used in messages for values that come from --set.
inline constexpr std::string_view override_file_name = "<--set>";

struct Cursor {
    const SceneContext* context = nullptr;
    YAML::Node node;          // undefined when the key is absent
    std::string schema_path;  // "components[].vibration"
    std::string field_path;   // "components[2].vibration"
    YAML::Mark mark;          // the value (scalars), the key (maps, lists), the parent (absent keys)

    bool present() const { return node.IsDefined() && !node.IsNull(); }
    bool is_map() const { return node.IsDefined() && node.IsMap(); }
    const SchemaEntry& entry() const;  // the schema entry of schema_path (must exist)

    Cursor child(std::string_view key) const;                                  // a fixed key of a map; absent if not there
    Cursor named_child(const YAML::Node& key, const YAML::Node& value) const;  // an entry of a named map
    Cursor item(std::size_t index) const;                                      // an item of a list
    std::size_t size() const { return node.IsDefined() && node.IsSequence() ? node.size() : 0; }
};

Cursor root_cursor(const SceneContext& context, const YAML::Node& root);

// YAML text read from `file`, parsed under the one nesting limit (yaml_load.h). A syntax error, or
// nesting past the limit, is an InputError at its line and column.
YAML::Node parse_yaml(const std::string& text, const std::string& file);

// "scene.yaml", line, column of the cursor (1-based), or "<--set>" for overridden fields.
SourceLocation location_of(const Cursor& at);

// Throws the InputError for a problem at `at` (adds which --set override it came from).
[[noreturn]] void fail(const Cursor& at, const std::string& problem);

// "'2 mm'", "a list", "a map", "nothing": what was found, for messages.
std::string describe_node(const YAML::Node& node);

// Schema-driven reads. An absent key takes the schema default; an absent required key, or an
// absent key without default for the non-optional reads, is an error at the parent map.
double read_quantity(const Cursor& c);
std::optional<double> read_optional_quantity(const Cursor& c);  // nullopt if absent and no default
long long read_integer(const Cursor& c);
Vec3 read_vector(const Cursor& c);
std::optional<Vec3> read_optional_vector(const Cursor& c);
std::optional<Vec3> read_optional_direction(const Cursor& c);  // normalised; the zero vector is an error
Mat3 read_matrix(const Cursor& c);
std::string read_text(const Cursor& c);    // "" if absent and no default
std::string read_choice(const Cursor& c);  // one of the entry's choices
std::vector<std::string> read_names(const Cursor& c);
// A table: one or more quantities, each checked against the entry's range. Empty if absent and no default.
std::vector<double> read_quantity_list(const Cursor& c);

}  // namespace peensim
