#include "scene/schema_validation.h"

#include <set>

namespace peensim {
namespace {

void check_node(const Cursor& c);

[[noreturn]] void fail_shape(const Cursor& c) { fail(c, "expected " + expected_text(c.entry()) + ", got " + describe_node(c.node)); }

// A map's keys must be plain scalars, each at most once (yaml-cpp keeps duplicates silently).
void check_keys_unique(const Cursor& c) {
    std::set<std::string> seen;
    for (const auto& kv : c.node) {
        Cursor at_key{c.context, kv.first, c.schema_path, c.field_path, kv.first.Mark()};
        if (!kv.first.IsScalar()) fail(at_key, "expected a plain key, got " + describe_node(kv.first));
        if (!seen.insert(kv.first.Scalar()).second) {
            at_key.field_path = schema_child_path(c.field_path, kv.first.Scalar());
            fail(at_key, "key '" + kv.first.Scalar() + "' appears more than once");
        }
    }
}

void check_fixed_map(const Cursor& c) {
    const SchemaEntry& e = c.entry();
    if (!c.node.IsDefined() || c.node.IsNull()) return;  // "key:" with nothing = an empty map
    if (c.node.IsScalar() && !e.choices.empty()) {
        for (std::string_view word : split_choices(e.choices))
            if (c.node.Scalar() == word) return;
    }
    if (!c.node.IsMap()) fail_shape(c);
    check_keys_unique(c);
    const std::vector<std::string_view> valid = schema_child_keys(c.schema_path);
    for (const auto& kv : c.node) {
        const std::string key = kv.first.Scalar();
        bool known = false;
        for (std::string_view v : valid) known = known || v == key;
        if (!known) {
            Cursor at_key{c.context, kv.first, c.schema_path, schema_child_path(c.field_path, key), kv.first.Mark()};
            const std::string where = c.field_path.empty() ? std::string("at the top level") : "in " + c.field_path;
            fail(at_key, "unknown key '" + key + "' " + where + "; valid keys: " + join_names(valid));
        }
        check_node(c.child(key));
    }
    for (std::string_view key : valid) {
        const Cursor child = c.child(key);
        if (child.entry().required && !child.node.IsDefined())
            fail(child, "missing required key '" + std::string(key) + "' (" + expected_text(child.entry()) + ")");
    }
}

void check_named_map(const Cursor& c) {
    if (!c.node.IsDefined() || c.node.IsNull()) return;
    if (!c.node.IsMap()) fail_shape(c);
    check_keys_unique(c);
    for (const auto& kv : c.node) {
        const Cursor child = c.named_child(kv.first, kv.second);
        if (!is_valid_name(kv.first.Scalar())) fail(child, "invalid name '" + kv.first.Scalar() + "'; names use only A-Z a-z 0-9 _ -");
        check_node(child);
    }
}

void check_list(const Cursor& c) {
    if (!c.node.IsDefined() || !c.node.IsSequence()) fail_shape(c);
    for (std::size_t i = 0; i < c.size(); ++i) check_node(c.item(i));
}

bool all_scalars(const YAML::Node& seq) {
    for (const YAML::Node& n : seq)
        if (!n.IsScalar()) return false;
    return true;
}

void check_node(const Cursor& c) {
    const SchemaEntry& e = c.entry();
    switch (e.kind) {
        case ValueKind::map: check_fixed_map(c); return;
        case ValueKind::named_map: check_named_map(c); return;
        case ValueKind::list: check_list(c); return;
        case ValueKind::quantity:
        case ValueKind::integer:
        case ValueKind::text:
        case ValueKind::choice:
            if (!c.node.IsScalar() || c.node.IsNull()) fail_shape(c);
            return;
        case ValueKind::vector3:
            if (c.node.IsScalar() && !c.node.IsNull()) return;
            if (!c.node.IsSequence() || !all_scalars(c.node)) fail_shape(c);
            return;
        case ValueKind::matrix3:
            if (!c.node.IsSequence()) fail_shape(c);
            return;  // rows are checked when read
        case ValueKind::name_list:
            if (!c.node.IsSequence() || !all_scalars(c.node)) fail_shape(c);
            return;
        case ValueKind::quantity_list:
            if (!c.node.IsSequence() || c.node.size() == 0 || !all_scalars(c.node)) fail_shape(c);
            return;
    }
}

}  // namespace

void check_structure(const Cursor& root) {
    if (!root.node.IsDefined() || root.node.IsNull()) fail(root, "the scene is empty; expected " + expected_text(root.entry()));
    check_node(root);
}

}  // namespace peensim
