// Writes a FemDeck as an Abaqus-format input deck (.inp), the dialect CalculiX (ccx 2.20) reads:
// the block's bricks (deck.block_element) and the shot's C3D8, node and element sets, element-face
// surfaces, an elastic-plastic target, elastic shot, a penalty node-to-surface contact pair (slave:
// the block's top, master: every shot's surface), the boundary conditions, the shot's initial
// velocities, one implicit *DYNAMIC step per group of impacts, each printing the surface profile's
// displacements (U) and the shot centres' velocities (V) to the .dat file at its end, and a final
// static relaxation step (contact removed, shot held) printing the residual dent (NPROFILE U) and
// the residual stresses of the column under the centre (EAXIS S, PEEQ). Set names are listed in
// docs/user-guide.md, "FEM hand-off".
#pragma once

#include <iosfwd>

#include "fem/fem_deck.h"

namespace peensim {

void write_inp(std::ostream& out, const FemDeck& deck);

}  // namespace peensim
