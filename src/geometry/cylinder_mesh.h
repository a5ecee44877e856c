// Generated circular cylinders: a solid rod, axle or disk (capped), or an open tube.
#pragma once

#include "geometry/axis_frame.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

struct CylinderSpec {
    double radius_m = 0.0;         // m, vertices lie on this circle (the polygon is inscribed)
    double height_m = 0.0;         // m, length along the axis
    int segments = 64;             // polygon sides around the axis (>= 3)
    Axis axis = Axis::z;           // world axis of the cylinder
    Vec3 center_m = Vec3::Zero();  // m, middle of the axis segment
    bool capped = true;            // false: an open tube (two boundary rims, not closed)
    int axial_subdivisions = 1;    // rings of quads along the axis (>= 1)
    int cap_rings = 1;             // rings per cap: 1 = a fan from the centre (>= 1)
};

// Normals point away from the axis and out through the caps (outward for a solid).
// Groups: "wall", "cap-low", "cap-high" (caps at the -axis and +axis ends).
// Angle 0 of the polygon lies along local u: +y for axis x, +z for axis y, +x for axis z.
// Throws InputError (field "cylinder") for a non-positive size or count.
TriangleMesh cylinder(const CylinderSpec& spec);

}  // namespace peensim
