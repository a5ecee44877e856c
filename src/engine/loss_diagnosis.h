// Why a shot left the assembly. A shot can only leave through an opening or through a surface the
// scheme failed to see. The flight that carried it out is an exact parabola from its last event,
// so the two can be told apart for certain: sweep the whole sphere (radius R, less a hair) along that
// flight against every component. If it touches nothing, the shot really passed through free
// space: the assembly has an opening at least one shot diameter wide there (a leak: a setup error,
// shown where the centre left the chamber's bounds). If it crosses a surface, the scheme missed a
// contact: an engine error, reported with the surface and the point it crossed.
#pragma once

#include "common/sim_time.h"
#include "engine/simulation_state.h"
#include "kernels/trajectory.h"
#include "model/model.h"

namespace peensim {

// path: the world flight of a shot of radius R (m) since its last event, times in seconds since
// `epoch` (t_from: that event; t_to: when it left the world box). Fills the diagnosis fields of `lost`.
void diagnose_loss(const Model& model, const SimTime& epoch, const Trajectory& path, double R, double t_from, double t_to, LostShot& lost);

}  // namespace peensim
