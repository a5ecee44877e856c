// The room a part takes in the chamber: its bounds, or, for a part turning about an axis, the
// bounds of the solid it sweeps. What `peensim new` sizes a chamber and a sonotrode around.
#pragma once

#include <optional>

#include "common/vec.h"
#include "geometry/axis_frame.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

struct PartEnvelope {
    Vec3 centre_m = Vec3::Zero();  // m, the middle of the part's own bounds (the turning axis passes through it)
    Vec3 size_m = Vec3::Zero();    // m, the part's own bounds (x, y, z)
    Vec3 lo_m = Vec3::Zero();      // m, the envelope's bounds: the part's, or its swept solid's
    Vec3 hi_m = Vec3::Zero();
    double swept_radius_m = 0.0;  // m, the farthest vertex from the turning axis (0: not turning)
    // m, the farthest the envelope reaches from the vertical (z) line through centre: the radius of
    // the smallest upright cylinder about that line that holds it.
    double footprint_radius_m = 0.0;
};

// Exact for the mesh's vertices: a vertex turning about the axis sweeps a circle, whose bounds
// and farthest point from the vertical line are closed-form (a triangle's interior lies within its
// corners' circles' hull for these bounds, as the bounds of a swept convex set are its corners').
PartEnvelope part_envelope(const TriangleMesh& mesh, std::optional<Axis> turning_axis);

}  // namespace peensim
