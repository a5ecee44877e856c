// The one schema of the scene file: every key, its type, unit, default, range and a line of doc.
// It drives the structural check (unknown keys, shapes, required keys), the defaults and range
// checks of the typed reads, the --set path check, and the Markdown reference (`peensim schema`).
//
// Paths: "shot.diameter"; "[]" for the items of a list ("components[].vibration.amplitude");
// "*" for the user-chosen names of a named map ("materials.*.density"). The root is "".
#pragma once

#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/range.h"
#include "common/units.h"

namespace peensim {

enum class ValueKind {
    map,            // fixed keys, described by the entries "<path>.<key>"
    named_map,      // user-chosen names -> entries described by "<path>.*"
    list,           // items described by "<path>[]"
    quantity,       // one number with a unit of `dimension`
    integer,        // a whole number
    vector3,        // [x, y, z] (each a quantity) or one string "x y z unit"
    matrix3,        // 3x3 matrix as three rows [[a, b, c], [d, e, f], [g, h, i]]
    text,           // free text, a name or a path
    choice,         // one word out of `choices`
    name_list,      // a list of names
    quantity_list,  // a list of one or more numbers with a unit of `dimension` (a table)
};

struct SchemaEntry {
    std::string_view path;
    ValueKind kind;
    Dimension dimension = Dimension::dimensionless;  // for quantity and vector3
    bool required = false;                           // the parent map must have this key
    std::string_view default_value;                  // text read like a value written in the file; "" = none
    std::string_view default_note;                   // for the reference when the default is not a plain value
    Range range;                                     // for quantity and integer
    std::string_view choices;                        // for choice: "a|b|c"; for map: the scalar form it also takes
    std::string_view planned;                        // for choice: values that are known but not available yet
    std::string_view plain_number_unit;              // unit of a number written without one ("" = SI)
    std::string_view doc;
};

// Every entry, in reference order (parents before children).
std::span<const SchemaEntry> scene_schema();

// The entry of a schema path, or nullptr.
const SchemaEntry* find_schema_entry(std::string_view path);

// The keys valid directly under a map entry ("process" -> duration, gravity, seed).
std::vector<std::string_view> schema_child_keys(std::string_view map_path);

// Component and material names: one or more of A-Z a-z 0-9 _ - (they appear in --set paths,
// contact keys and output file names).
bool is_valid_name(std::string_view name);

// "a|b|c" -> {"a", "b", "c"}.
std::vector<std::string_view> split_choices(std::string_view choices);

// Joins names as "a, b, c".
std::string join_names(const std::vector<std::string_view>& names);

// Schema path of a child: ("", "shot") -> "shot"; ("shot", "count") -> "shot.count".
std::string schema_child_path(std::string_view parent, std::string_view key);

// What a node of this entry should look like, for "expected ..., got ..." messages.
std::string expected_text(const SchemaEntry& entry);

// The Markdown reference of the scene file format (a table of every key, then the units).
std::string scene_reference_markdown();

}  // namespace peensim
