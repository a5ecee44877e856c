// --set overrides: "path=value" applied to the scene's YAML tree before it is checked, so every
// check applies to overridden values too. The path uses the schema's keys, with list items
// selected by name or by index: "process.duration=0.2", "components[gear].motion.speed=60 rpm",
// "components[2].mesh_unit=mm", "output.log=[gear, axle]". The value is read as YAML.
#pragma once

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "scene/yaml_access.h"

namespace peensim {

// Applies the overrides in order (a later one wins) and records in `context.overrides` which fields
// they set or created. Throws InputError (file "<--set>", field = the override's path) for a
// malformed override, a path the schema does not know or a list item that does not exist.
void apply_overrides(YAML::Node root, const std::vector<std::string>& overrides, SceneContext& context);

// The schema entry an override path sets ("components[gear].motion.speed" ->
// "components[].motion.speed", "materials.steel.density" -> "materials.*.density"); nullptr for a
// malformed path or one the schema does not know (apply_overrides says why).
const SchemaEntry* override_schema_entry(const std::string& path);

}  // namespace peensim
