#include "app/sweep/sweep_values.h"

#include <cmath>
#include <map>

#include <yaml-cpp/yaml.h>

#include "common/units.h"
#include "scene/overrides.h"
#include "scene/schema.h"
#include "scene/yaml_load.h"

namespace peensim {

namespace {

// Above this a double no longer holds every whole number: two different seeds could agree.
constexpr double kExactWholeNumbers = 9007199254740992.0;  // 2^53

bool numeric(const SchemaEntry* e) {
    return e != nullptr && (e->kind == ValueKind::quantity || e->kind == ValueKind::integer || e->kind == ValueKind::vector3 ||
                            e->kind == ValueKind::quantity_list);
}

std::string key_of(const YAML::Node& n, const SchemaEntry* e) {
    if (n.IsScalar()) {
        if (!numeric(e)) return n.Scalar();
        try {
            const double v = parse_quantity(n.Scalar(), e->dimension, e->plain_number_unit);
            if (e->kind == ValueKind::integer && !(std::abs(v) < kExactWholeNumbers)) return n.Scalar();
            return format_si(v);
        } catch (const QuantityError&) {
            return n.Scalar();
        }
    }
    if (n.IsSequence()) {
        // A list's items have entries of their own; a vector's or a table's numbers, the field's.
        const SchemaEntry* item = e != nullptr && e->kind == ValueKind::list ? find_schema_entry(std::string(e->path) + "[]") : e;
        std::string s = "[";
        for (const YAML::Node& x : n) s += (s.size() > 1 ? ", " : "") + key_of(x, item);
        return s + "]";
    }
    if (n.IsMap()) {
        std::map<std::string, std::string> entries;  // sorted: key order does not change a map
        for (const auto& kv : n) {
            const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : key_of(kv.first, nullptr);
            const SchemaEntry* child = e == nullptr                      ? nullptr
                                       : e->kind == ValueKind::map       ? find_schema_entry(schema_child_path(e->path, key))
                                       : e->kind == ValueKind::named_map ? find_schema_entry(schema_child_path(e->path, "*"))
                                                                         : nullptr;
            entries[key] = key_of(kv.second, child);
        }
        std::string s = "{";
        for (const auto& [key, value] : entries) s += (s.size() > 1 ? ", " : "") + key + ": " + value;
        return s + "}";
    }
    return "~";
}

}  // namespace

std::string sweep_value_key(const std::string& path, const std::string& text) {
    try {
        return key_of(load_yaml(text), override_schema_entry(path));
    } catch (const YAML::Exception&) {
        return text;  // not YAML: its check says so
    }
}

}  // namespace peensim
