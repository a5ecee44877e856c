// The shot as a meshed ball of 8-node bricks: a cube grid of `divisions` cells a side mapped onto
// the ball shell by shell (equiangular on each shell, so the surface cells are near squares and the
// pole the shot lands on sits at the middle of a face, not at a corner), blended towards a cube at
// the centre so that no brick degenerates. Centred at the origin; a quarter ball keeps x >= 0,
// y >= 0 (symmetry planes x = 0 and y = 0). Pure computation: no I/O.
#pragma once

#include <vector>

#include "fem/hex_mesh.h"

namespace peensim {

struct SphereMesh {
    HexMesh mesh;
    std::vector<HexFace> surface;  // the faces on the ball's surface
    int centre_node = 0;           // the node at the centre (its velocity is the shot's)
    std::vector<int> x0, y0;       // nodes on x = 0 and y = 0 (the quarter ball's symmetry planes)
};

// `divisions`: cells along a cube edge, even and >= 2. Throws std::invalid_argument otherwise or
// for a non-positive radius.
SphereMesh mesh_sphere(double radius_m, int divisions, bool quarter);

}  // namespace peensim
