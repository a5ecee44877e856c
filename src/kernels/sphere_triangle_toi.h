// Exact time of impact of a sphere on a ballistic path with a static triangle: the first moment
// the distance from the centre to the triangle falls to the radius. Each feature gives a
// polynomial gap: the face a quadratic (signed distance to the plane = +-R, foot inside), each edge
// a quartic (distance to the line = R, foot on the segment), each vertex a quartic; the earliest
// valid root of all is the first contact. Pure computation, no allocation.
#pragma once

#include "common/vec.h"
#include "kernels/closest_point.h"
#include "kernels/toi_status.h"
#include "kernels/trajectory.h"

namespace peensim {

struct TriangleContact {
    double time = 0.0;            // s
    Vec3 point = Vec3::Zero();    // m, the triangle's point closest to the centre
    Vec3 normal = Vec3::UnitZ();  // unit, from `point` towards the centre
    TriangleFeature feature = TriangleFeature::face;
};

// The first contact of a sphere of `radius` (m, > 0) moving on `path` with the triangle (a, b, c)
// (m, same frame as the path) in [t_begin, t_end] (s):
// - overlapping: the gap at t_begin is below -kStartTouchFraction * radius; `out` describes the
//   closest point then (time = t_begin).
// - impact: the earliest time the sphere reaches the triangle while approaching, or touches it
//   tangentially (a graze). A sphere that starts touching (|gap| within the tolerance) and
//   approaching, or at rest and pulled in by g, is an impact at t_begin; one that starts touching
//   and separating, as right after a bounce, is not: only a later return counts.
// - miss: neither.
ToiStatus sphere_triangle_toi(const Trajectory& path, double radius, const Vec3& a, const Vec3& b, const Vec3& c, double t_begin,
                              double t_end, TriangleContact& out);

// The search alone: the earliest time in [t_from, t_to] at which the gap falls to zero from
// above or touches zero, without reading the state at t_from. For callers that know the sphere
// is clear of the triangle at t_from (the BVH walk starts it where the sphere enters a leaf's box
// grown by the radius). True if found.
bool sphere_triangle_first_touch(const Trajectory& path, double radius, const Vec3& a, const Vec3& b, const Vec3& c, double t_from,
                                 double t_to, TriangleContact& out);

}  // namespace peensim
