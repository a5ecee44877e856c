// Writes a FemDeck as an Abaqus-format input deck (.inp), the dialect CalculiX (ccx 2.20) reads:
// C3D8 bricks, node and element sets, element-face surfaces, an elastic-plastic target, elastic
// shot, a penalty surface-to-surface contact pair (slave: the block's top, master: every shot's
// surface), the boundary conditions, the shot's initial velocities and one implicit *DYNAMIC
// step per group of impacts, each printing the surface profile's displacements (U) and the shot
// centres' velocities (V) to the .dat file at its end. Set names are listed in the README.
#pragma once

#include <iosfwd>

#include "fem/fem_deck.h"

namespace peensim {

void write_inp(std::ostream& out, const FemDeck& deck);

}  // namespace peensim
