#include "model/kinematics.h"

#include <cmath>

namespace peensim {

Pose Kinematics::pose(const SimTime& t, double offset_s) const {
    switch (kind) {
        case Kind::fixed: return rest;
        case Kind::vibrating: return {rest.rotation, rest.translation + axis * displacement(t, offset_s)};
        case Kind::rotating: {
            // The angle is reduced modulo 2 pi from the compensated time so long runs keep it exact.
            const double turns = t.cycle_fraction(omega_rad_per_s / (2.0 * M_PI), offset_s);
            const Mat3 spin = Eigen::AngleAxisd(2.0 * M_PI * turns, axis_direction).toRotationMatrix();
            return {spin * rest.rotation, axis_point_m + spin * (rest.translation - axis_point_m)};
        }
    }
    return rest;
}

Vec3 Kinematics::point_velocity(const Vec3& x_w, const SimTime& t, double offset_s) const {
    switch (kind) {
        case Kind::fixed: return Vec3::Zero();
        case Kind::vibrating: return axis * displacement_rate(t, offset_s);
        case Kind::rotating: return omega_rad_per_s * axis_direction.cross(x_w - axis_point_m);
    }
    return Vec3::Zero();
}

Vec3 Kinematics::point_acceleration(const Vec3& x_w, const SimTime& t, double offset_s) const {
    switch (kind) {
        case Kind::fixed: return Vec3::Zero();
        case Kind::vibrating: return axis * displacement_accel(t, offset_s);
        case Kind::rotating: {
            const Vec3 r = x_w - axis_point_m;
            const Vec3 radial = r - axis_direction.dot(r) * axis_direction;
            return -omega_rad_per_s * omega_rad_per_s * radial;
        }
    }
    return Vec3::Zero();
}

double Kinematics::peak_surface_speed(double max_radius_m) const {
    switch (kind) {
        case Kind::fixed: return 0.0;
        case Kind::vibrating: return std::abs(amplitude_m * angular_frequency());
        case Kind::rotating: return std::abs(omega_rad_per_s) * max_radius_m;
    }
    return 0.0;
}

}  // namespace peensim
