// Initial shot positions and velocities (reference sec. 2: random, non-overlapping, on the
// sonotrode at t = 0). Shot are dropped at random points of the sonotrode's upper faces, one
// radius (plus 1 %) above them, rejected if outside the chamber's cavity (beyond the walls, inside
// a closed part, in a sealed pocket) or touching a mesh or another shot; when a layer is full (400
// rejections in a row) the next layer is filled one diameter higher, until the shot are placed or
// no layer takes any more. A mix is spaced by its largest diameter; each shot draws its size.
#pragma once

#include <vector>

#include "common/vec.h"
#include "model/model.h"
#include "model/shot_cavity.h"

namespace peensim {

struct InitialShots {
    std::vector<Vec3> positions;   // m, world
    std::vector<Vec3> velocities;  // m/s, world
    std::vector<int> sizes;        // index into Model::shot_sizes
    int layers = 0;                // layers used
};

// Throws InputError if the chamber is not closed around the sonotrode or the shot do not fit.
InitialShots place_shots(const Model& model);
// The same in a cavity already built, drawing from the generator it was built with.
InitialShots place_shots(const Model& model, ShotCavity& cavity, Random& rng);

}  // namespace peensim
