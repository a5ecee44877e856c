// What differs between the scene a run was made with and the one it is now given, in words, for
// the refusals that compare their hashes (`peensim run --resume`, a sweep run again over its
// finished runs): "shot: diameter: 0.002 -> 0.0015" says what to undo, where "another scene"
// left the user to diff the files.
#pragma once

#include <string>

#include "scene/scene_description.h"

namespace peensim {

// The first simulated setting that differs between the run's scene.resolved.yaml (its path) and
// `now`: "<section>[, entry <name>]: the run had `<line>`, now `<line>`" (the lines as the
// resolved scene writes them, in SI); when the settings are the same, the mesh files written after
// that file (the run's start), or that a mesh file's bytes differ; "" when nothing can be said (no
// readable resolved scene: a damaged file, its meshes gone).
std::string scene_difference(const std::string& resolved_yaml_path, const SceneDescription& now);

}  // namespace peensim
