// The picture `peensim check --render FILE.png` draws: the assembly at t = 0 from the scene's
// camera (its `render` block) or the automatic front-above framing of the chamber, components in
// their role colours with the chamber's near walls cut away, and the shot where they start. A
// misplaced part is seen before a run. Where the checks found meshes crossing, the point is marked
// (a red ball, numbered) and its message listed under the title.
#pragma once

#include <string>

#include "engine/simulation_state.h"
#include "model/assembly_checks.h"
#include "model/model.h"

namespace peensim {

// Writes the PNG (width x height pixels). Throws std::runtime_error on a rendering or file failure.
void draw_assembly_picture(const Model& model, const SimulationState& start, const std::vector<AssemblyIssue>& issues,
                           const std::string& png_path, int width_px, int height_px);

}  // namespace peensim
