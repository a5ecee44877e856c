// A closed, watertight involute spur gear with a central bore, extruded along its axis.
//
// Layout in the gear's plane (local u, v; the axis is local w, see axis_frame.h): tooth k is
// centred on angle 2 pi k / z from +u (for axis y, +u is +z: tooth 0 points up). The end faces
// are structured quads: a polar grid from the bore to the root circle, and on each tooth a
// grid whose rows are circles of the flank sampling and whose columns split the tooth width
// evenly, so the tip land, the flanks and the end faces share their vertices exactly.
// Normals point out of the solid (into the bore on the bore wall).
//
// Groups: "tooth-<k>", k = 0 .. z - 1, each the angular sector [2 pi (k - 1/2) / z,
// 2 pi (k + 1/2) / z) around tooth k, through the whole body (bore wall, end faces, flanks).
#pragma once

#include "geometry/spur_gear_profile.h"
#include "geometry/spur_gear_resolution.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

// Throws InputError (field "gear") for an impossible gear or a resolution below its minimums.
TriangleMesh spur_gear(const SpurGearSpec& spec, const SpurGearResolution& resolution);

}  // namespace peensim
