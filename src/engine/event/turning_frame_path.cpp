#include "engine/event/turning_frame_path.h"

#include <cmath>
#include <limits>

namespace peensim {

double TurningFramePath::stretch_within(double distance) const {
    if (!(jerk_bound > 0.0)) return std::numeric_limits<double>::infinity();
    return std::cbrt(6.0 * distance / jerk_bound);
}

TurningFramePath turning_frame_path(const Kinematics& kin, const SimTime& epoch, const Trajectory& path, double u, double u_end) {
    // The component frame's coordinates of a world point x are Q(t) (x - P) + constants, Q the
    // inverse of the turn: Q' = -Q [w]x with w = omega u_axis. With y = c - P (c the centre,
    // y' = v, y'' = g, y''' = 0):
    //   x'   = Q (v - w x y)
    //   x''  = Q (g - 2 w x v + w x (w x y))
    //   x''' = Q (-3 w x g + 3 w x (w x v) - w x (w x (w x y)))
    // so |x'''| <= 3 |w| |g| + 3 |w|^2 |v| + |w|^3 |y_perp|, |y_perp| the distance to the axis.
    const Vec3 w = kin.omega_rad_per_s * kin.axis_direction;
    const Pose pose = kin.pose(epoch, u);
    const Mat3 q = pose.rotation.transpose();
    const Vec3 c = path.position(u), v = path.velocity(u);
    const Vec3 y = c - kin.axis_point_m;
    TurningFramePath out;
    out.parabola = Trajectory{pose.to_component(c), q * (v - w.cross(y)), q * (path.g - 2.0 * w.cross(v) + w.cross(w.cross(y))), u};
    const double span = std::max(0.0, u_end - u);      // s
    const double speed = path.max_speed(u, u + span);  // m/s, the centre's largest over the span
    const double radius = (y - y.dot(kin.axis_direction) * kin.axis_direction).norm() + speed * span;  // m, from the axis
    const double om = std::abs(kin.omega_rad_per_s), g = path.g.norm();
    // 1 % over the bound: the rounding of the parabola's coefficients, far inside it.
    out.jerk_bound = 1.01 * (3.0 * om * g + 3.0 * om * om * speed + om * om * om * radius);
    return out;
}

}  // namespace peensim
