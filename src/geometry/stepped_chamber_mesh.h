// The gear case's chamber: a two-section cylindrical cavity with a vertical (z) axis through
// the origin, open at the bottom where the sonotrode disk closes it.
//
//        lid (z = lid_z)
//      +----------------+          upper section, radius upper_radius, step_z .. lid_z
//      |                |
//      +--+          +--+  step    annulus at z = step_z from lower_radius to upper_radius
//         |          |             lower section, radius lower_radius, bottom_z .. step_z
//         +  open    +  (z = bottom_z)
//
// A single layer of triangles (no wall thickness). Normals point INTO THE CAVITY (the side
// the shot sees): walls towards the axis, the step up (+z), the lid down (-z). Closing the
// bottom with a disk facing +z gives a closed mesh whose enclosed_volume is minus the volume
// of the cavity.
#pragma once

#include "geometry/triangle_mesh.h"

namespace peensim {

struct SteppedChamberSpec {
    double lower_radius_m = 0.0;  // m, r1 (vertices on the circle: inscribed polygon)
    double upper_radius_m = 0.0;  // m, r2 > r1
    double bottom_z_m = 0.0;      // m, z0: the open rim
    double step_z_m = 0.0;        // m, z1 > z0
    double lid_z_m = 0.0;         // m, z2 > z1
    int segments = 128;           // polygon sides around the axis (>= 3)
    int lower_layers = 1;         // rings of quads on the lower wall (>= 1)
    int upper_layers = 1;         // rings of quads on the upper wall (>= 1)
    int step_rings = 1;           // rings of quads on the step annulus (>= 1)
    int lid_rings = 1;            // rings on the lid; 1 = a fan from the centre (>= 1)
};

// Groups: "lower-wall", "step", "upper-wall", "lid".
// Throws InputError (field "chamber") unless 0 < r1 < r2, z0 < z1 < z2 and the counts are valid.
TriangleMesh stepped_tube_chamber(const SteppedChamberSpec& spec);

}  // namespace peensim
