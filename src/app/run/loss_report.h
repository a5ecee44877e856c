// The message a user reads for each lost shot: a leak of the assembly (where, how wide at least:
// fix the meshes or their placement) or an engine error (which surface it crossed: report it).
#pragma once

#include <string>

#include "engine/simulation_state.h"
#include "model/model.h"

namespace peensim {

std::string describe_loss(const Model& model, const LostShot& lost);

}  // namespace peensim
