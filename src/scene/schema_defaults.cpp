#include "scene/schema_defaults.h"

#include <stdexcept>

#include "scene/scene_sections.h"
#include "scene/yaml_access.h"

namespace peensim {
namespace {

// No place in a file: location_of() gives line and column 0.
YAML::Mark nowhere() {
    YAML::Mark m;
    m.line = m.column = -1;
    return m;
}

// A cursor on the key at `path`, left out: the typed reads then return the schema's default.
Cursor absent_key(const SceneContext& context, std::string_view path, std::initializer_list<ValueKind> kinds) {
    const SchemaEntry* e = find_schema_entry(path);
    if (e == nullptr) throw std::logic_error("no schema entry '" + std::string(path) + "'");
    if (e->default_value.empty()) throw std::logic_error("schema entry '" + std::string(path) + "' has no default");
    bool kind_ok = false;
    for (ValueKind k : kinds) kind_ok = kind_ok || e->kind == k;
    if (!kind_ok) throw std::logic_error("schema entry '" + std::string(path) + "' is not of the kind asked for");
    return Cursor{&context, YAML::Node(YAML::NodeType::Undefined), std::string(path), std::string(path), nowhere()};
}

}  // namespace

double schema_default_quantity(std::string_view path) {
    const SceneContext context;
    return read_quantity(absent_key(context, path, {ValueKind::quantity}));
}

long long schema_default_integer(std::string_view path) {
    const SceneContext context;
    return read_integer(absent_key(context, path, {ValueKind::integer}));
}

Vec3 schema_default_vector(std::string_view path) {
    const SceneContext context;
    return read_vector(absent_key(context, path, {ValueKind::vector3}));
}

std::string schema_default_word(std::string_view path) {
    const SceneContext context;
    const Cursor c = absent_key(context, path, {ValueKind::choice, ValueKind::text});
    return c.entry().kind == ValueKind::choice ? read_choice(c) : read_text(c);
}

RenderDesc default_render() {
    const SceneContext context;
    const YAML::Node empty_block(YAML::NodeType::Map);
    return *read_render(Cursor{&context, empty_block, "render", "render", nowhere()});
}

}  // namespace peensim
