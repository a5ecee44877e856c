// The schema's defaults as values: what a key left out of a scene gets, in SI, read exactly as the
// parser reads an absent key (yaml_access.h). Code that needs a scene default outside a scene file
// takes it from here rather than writing the number again, so the schema stays its one source.
#pragma once

#include <string>
#include <string_view>

#include "common/vec.h"
#include "scene/scene_description.h"

namespace peensim {

// The default of the schema entry at `path` ("render.fps", "contacts.*.law"). Asking for an entry
// that has no default, or of another kind, is a programming error: std::logic_error.
double schema_default_quantity(std::string_view path);  // SI
long long schema_default_integer(std::string_view path);
Vec3 schema_default_vector(std::string_view path);       // SI
std::string schema_default_word(std::string_view path);  // a choice or a text

// The render settings of a scene whose `render` block is empty: every key at its schema default.
// What `run --render` records with when the scene has no block.
RenderDesc default_render();

}  // namespace peensim
