// Readers of the scene file's sections (internal to src/scene). Each takes the cursor of its
// section in a tree that has passed check_structure, reads through the schema-driven reads of
// yaml_access.h, and checks what the schema alone cannot (either-or keys, roles, references).
#pragma once

#include <filesystem>

#include "scene/scene_description.h"
#include "scene/yaml_access.h"

namespace peensim {

ProcessDesc read_process(const Cursor& process);
AccuracyDesc read_accuracy(const Cursor& accuracy);
std::vector<MaterialDesc> read_materials(const Cursor& materials);
// Needs the materials (the shot may name one for its density).
ShotDesc read_shot(const Cursor& shot, const std::vector<MaterialDesc>& materials);
// Needs the materials ("shot-<material>" keys must name one). Ends with a "default" entry.
std::vector<ContactPairDesc> read_contacts(const Cursor& contacts, const std::vector<MaterialDesc>& materials);
// Mesh paths are resolved against `scene_dir`; roles, names and material references are checked.
std::vector<ComponentDesc> read_components(const Cursor& components, const std::filesystem::path& scene_dir,
                                           const std::vector<MaterialDesc>& materials);
// A component's `regions` list (names unique on the component, axes and boxes checked).
std::vector<RegionDesc> read_regions(const Cursor& regions);
// The `sources` and `sinks` lists (names unique among both; a source stops at the run's end
// unless it says otherwise).
// shot_mass_kg: one shot's mass (a mass flow's rate); up: against gravity (+z without it), the
// default target normal.
// A mesh file named by `mesh`, resolved against the scene's directory; refused if it does not exist.
std::string resolve_mesh(const Cursor& mesh, const std::filesystem::path& scene_dir);

void read_flow(const Cursor& sources, const Cursor& sinks, double duration_s, double shot_mass_kg, const Vec3& up,
               const std::filesystem::path& scene_dir, std::vector<SourceDesc>& out_sources, std::vector<SinkDesc>& out_sinks);
// The `air` block (defaults: still air at 20 C, no drag).
AirDesc read_air(const Cursor& air);
// Needs the components (the logged names must be components; the default logs every part) and
// the run's duration (s; what the shot-position series plans).
OutputDesc read_output(const Cursor& output, const std::vector<ComponentDesc>& components, double duration_s);

// The `render` block, or nullopt when the scene has none.
std::optional<RenderDesc> read_render(const Cursor& render);

// "a, b, c" of the materials' names, for messages.
std::string material_names(const std::vector<MaterialDesc>& materials);
const MaterialDesc* find_material(const std::vector<MaterialDesc>& materials, const std::string& name);

}  // namespace peensim
