// A shot's flight seen from a turning part. In the part's own frame the centre follows no parabola
// (the frame turns under it), but over a short stretch it stays close to one: its Taylor parabola
// at u, off by at most M tau^3 / 6 at u + tau, M bounding the third derivative over the stretch.
// A static sweep of that parabola with the radius grown by M tau^3 / 6 (MeshCollider::first_hit)
// can then only be early: no contact with the part before the time it returns. The wall
// predictor's conservative advancement on a turning part jumps by it (wall_predictor.cpp).
#pragma once

#include "common/sim_time.h"
#include "kernels/trajectory.h"
#include "model/kinematics.h"

namespace peensim {

struct TurningFramePath {
    Trajectory parabola;      // component frame: position, velocity and acceleration of the centre at u
    double jerk_bound = 0.0;  // m/s^3, M: the largest |x'''| of the centre in the component frame over [u, u_end]

    // m, how far the centre can be from the parabola tau (s, >= 0) after u.
    double deviation(double tau) const { return jerk_bound * tau * tau * tau / 6.0; }
    // s, the longest stretch after u whose deviation stays within `distance` (m).
    double stretch_within(double distance) const;
};

// `path` (world) seen from component kinematics `kin` (Kind::rotating, constant omega), at u (s
// since `epoch`), the bound taken over [u, u_end].
TurningFramePath turning_frame_path(const Kinematics& kin, const SimTime& epoch, const Trajectory& path, double u, double u_end);

}  // namespace peensim
