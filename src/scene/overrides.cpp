#include "scene/overrides.h"

#include <algorithm>
#include <cctype>

#include "scene/yaml_load.h"

namespace peensim {
namespace {

struct PathStep {
    bool is_selector = false;  // "[name]" or "[2]" rather than ".key"
    std::string text;
};

// One override being applied; its errors all point at "<--set>" and name its path.
struct OverrideWalk {
    std::string text;  // "path=value" as given
    std::string path;  // the part before '='
    std::vector<PathStep> steps;
    YAML::Node value;
    SceneContext* context = nullptr;

    [[noreturn]] void fail(const std::string& problem) const {
        throw InputError(SourceLocation{std::string(override_file_name), 0, 0}, path, problem + " (in --set '" + text + "')");
    }
    void record(const std::string& field_path) const { context->overrides.push_back({field_path, text}); }
};

std::string trimmed_text(const std::string& s) {
    const auto first = s.find_first_not_of(" \t");
    if (first == std::string::npos) return std::string();
    return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

std::vector<PathStep> split_path(const OverrideWalk& w) {
    std::vector<PathStep> steps;
    const std::string& p = w.path;
    std::size_t i = 0;
    while (i < p.size()) {
        if (p[i] == '[') {
            const std::size_t close = p.find(']', i);
            if (close == std::string::npos) w.fail("'[' without ']'");
            const std::string sel = trimmed_text(p.substr(i + 1, close - i - 1));
            if (sel.empty() || steps.empty()) w.fail("expected [name] or [index] after a list key");
            steps.push_back({true, sel});
            i = close + 1;
            if (i < p.size() && p[i] != '.' && p[i] != '[') w.fail("expected '.' or '[' after ']'");
            if (i < p.size() && p[i] == '.') ++i;
            continue;
        }
        const std::size_t end = p.find_first_of(".[", i);
        const std::string key = p.substr(i, end == std::string::npos ? std::string::npos : end - i);
        if (key.empty()) w.fail("empty key in the path");
        steps.push_back({false, key});
        if (end == std::string::npos) break;
        i = p[end] == '.' ? end + 1 : end;
        if (p[end] == '.' && i == p.size()) w.fail("the path ends with '.'");
    }
    if (steps.empty()) w.fail("empty path before '='");
    return steps;
}

bool is_index(const std::string& s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

std::size_t select_item(const OverrideWalk& w, const YAML::Node& list, const std::string& sel, const std::string& field_path) {
    if (is_index(sel)) {
        // Compared as text first: an index of 20 digits must not overflow on its way to a range error.
        const std::size_t index = sel.size() <= 9 ? std::stoul(sel) : list.size();
        if (index >= list.size())
            w.fail("index " + sel + " is out of range: " + field_path + " has " + std::to_string(list.size()) + " items");
        return index;
    }
    std::string names;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const YAML::Node name = list[i].IsMap() ? list[i]["name"] : YAML::Node();
        if (!name.IsDefined() || !name.IsScalar()) continue;
        if (name.Scalar() == sel) return i;
        names += (names.empty() ? "" : ", ") + name.Scalar();
    }
    w.fail("no item named '" + sel + "' in " + field_path + " (names: " + names + ")");
}

// Sets the value at steps[i..] below `node` (whose entry is `schema_path`). Recursion, not a loop:
// assigning one yaml-cpp Node variable to another would overwrite the tree instead of moving down.
void set_at(YAML::Node node, std::size_t i, const std::string& schema_path, const std::string& field_path, const OverrideWalk& w) {
    const PathStep& step = w.steps[i];
    const bool last = i + 1 == w.steps.size();
    const SchemaEntry* entry = find_schema_entry(schema_path);
    const std::string where = field_path.empty() ? std::string("the top level") : field_path;

    if (step.is_selector) {
        if (entry == nullptr || entry->kind != ValueKind::list)
            w.fail("'" + where + "' is not a list, so [" + step.text + "] selects nothing");
        if (!node.IsSequence()) w.fail("'" + where + "' is " + describe_node(node) + ", not a list");
        const std::size_t index = select_item(w, node, step.text, where);
        const std::string child_field = field_path + "[" + std::to_string(index) + "]";
        if (last) {
            node[index] = w.value;
            w.record(child_field);
            return;
        }
        set_at(node[index], i + 1, schema_path + "[]", child_field, w);
        return;
    }

    std::string child_schema;
    if (entry != nullptr && entry->kind == ValueKind::map) {
        const std::vector<std::string_view> valid = schema_child_keys(schema_path);
        if (std::find(valid.begin(), valid.end(), step.text) == valid.end())
            w.fail("unknown key '" + step.text + "' in " + where + "; valid keys: " + join_names(valid));
        child_schema = schema_child_path(schema_path, step.text);
    } else if (entry != nullptr && entry->kind == ValueKind::named_map) {
        if (!is_valid_name(step.text)) w.fail("invalid name '" + step.text + "'; names use only A-Z a-z 0-9 _ -");
        child_schema = schema_child_path(schema_path, "*");
    } else {
        w.fail("'" + where + "' has no keys (it is " + (entry ? expected_text(*entry) : std::string("unknown")) + ")");
    }
    if (node.IsDefined() && !node.IsNull() && !node.IsMap())
        w.fail("'" + where + "' is " + describe_node(node) + ", not a map; set it as a whole instead");

    const std::string child_field = schema_child_path(field_path, step.text);
    if (last) {
        node[step.text] = w.value;
        w.record(child_field);
        return;
    }
    const YAML::Node& const_node = node;  // const look-up: no empty entry is inserted
    const YAML::Node existing = const_node[step.text];
    if (!existing.IsDefined() || existing.IsNull()) {
        if (w.steps[i + 1].is_selector) w.fail("there is no list '" + child_field + "' to select from");
        node[step.text] = YAML::Node(YAML::NodeType::Map);
        w.record(child_field);  // created by this override
    }
    set_at(node[step.text], i + 1, child_schema, child_field, w);
}

}  // namespace

const SchemaEntry* override_schema_entry(const std::string& path) {
    OverrideWalk w;
    w.text = w.path = trimmed_text(path);
    try {
        w.steps = split_path(w);
    } catch (const InputError&) {
        return nullptr;
    }
    std::string schema_path;
    for (const PathStep& step : w.steps) {
        const SchemaEntry* entry = find_schema_entry(schema_path);
        if (step.is_selector) {
            if (entry == nullptr || entry->kind != ValueKind::list) return nullptr;
            schema_path += "[]";
        } else if (entry != nullptr && entry->kind == ValueKind::named_map) {
            schema_path = schema_child_path(schema_path, "*");
        } else {
            schema_path = schema_child_path(schema_path, step.text);
        }
    }
    return find_schema_entry(schema_path);
}

void apply_overrides(YAML::Node root, const std::vector<std::string>& overrides, SceneContext& context) {
    for (const std::string& text : overrides) {
        OverrideWalk w;
        w.text = text;
        w.context = &context;
        const std::size_t eq = text.find('=');
        w.path = trimmed_text(text.substr(0, eq));
        if (eq == std::string::npos) w.fail("expected path=value");
        const std::string value_text = trimmed_text(text.substr(eq + 1));
        if (value_text.empty()) w.fail("missing value after '='");
        try {
            w.value = load_yaml(value_text);
        } catch (const YAML::Exception& e) {
            w.fail("the value is not valid YAML: " + e.msg);
        }
        w.steps = split_path(w);
        set_at(root, 0, "", "", w);
    }
}

}  // namespace peensim
