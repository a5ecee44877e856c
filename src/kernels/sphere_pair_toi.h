// Exact time of impact of two shot on ballistic paths: under the same gravity their relative
// motion is linear, so |dp + dv u|^2 = (R1 + R2)^2 is a quadratic, solved in closed form.
// Pure computation, no allocation.
#pragma once

#include "common/vec.h"
#include "kernels/toi_status.h"
#include "kernels/trajectory.h"

namespace peensim {

struct PairContact {
    double time = 0.0;            // s
    Vec3 normal = Vec3::UnitZ();  // unit, from the first sphere's centre towards the second's
};

// The first contact of spheres of radii r1, r2 (m) on paths p1, p2 (same frame, their t0 may differ)
// in [t_begin, t_end] (s). Equal accelerations (two flying shot) give a quadratic in closed form;
// different ones (a shot at rest, g = 0, and a flying one) a quartic solved by polynomial_roots.
// - overlapping: the gap at t_begin is below -kStartTouchFraction * (r1 + r2) (time = t_begin);
// - impact: the earliest time they touch while approaching, or graze; touching at t_begin
//   (|gap| within the tolerance) counts only while approaching (spheres that separate on a line
//   never meet again);
// - miss: neither.
ToiStatus sphere_pair_toi(const Trajectory& p1, double r1, const Trajectory& p2, double r2, double t_begin, double t_end, PairContact& out);

}  // namespace peensim
