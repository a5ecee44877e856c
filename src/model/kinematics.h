// Closed-form motion of a component (reference sec. 2, "Kinematics in closed form"):
// pose and surface velocity at any time come from formulas, never from differences over a step.
//   fixed:      x_w = R0 x_c + T0
//   vibrating:  x_w = R0 x_c + T0 + a * A sin(2 pi F t + phase)        (sonotrode)
//   rotating:   x_w = P + Rot(u, omega t) (R0 x_c + T0 - P)            (part about axis u through P)
#pragma once

#include "common/sim_time.h"
#include "common/vec.h"

namespace peensim {

struct Pose {
    Mat3 rotation = Mat3::Identity();  // component frame -> world
    Vec3 translation = Vec3::Zero();   // m

    Vec3 to_world(const Vec3& x_c) const { return rotation * x_c + translation; }
    Vec3 to_component(const Vec3& x_w) const { return rotation.transpose() * (x_w - translation); }
};

struct Kinematics {
    enum class Kind { fixed, vibrating, rotating };
    Kind kind = Kind::fixed;
    Pose rest;  // pose at t = 0 without vibration

    // vibrating
    Vec3 axis = Vec3::UnitZ();  // unit, world
    double amplitude_m = 0.0;   // m, A0
    double frequency_hz = 0.0;  // Hz, F
    double phase_rad = 0.0;     // rad

    // rotating
    Vec3 axis_point_m = Vec3::Zero();     // m, P
    Vec3 axis_direction = Vec3::UnitZ();  // unit, u
    double omega_rad_per_s = 0.0;         // rad/s

    bool moves() const { return kind != Kind::fixed && (amplitude_m != 0.0 || omega_rad_per_s != 0.0); }

    // Sonotrode displacement along `axis` (m) and its time derivatives at t + offset.
    double displacement(const SimTime& t, double offset_s = 0.0) const { return amplitude_m * std::sin(angle(t, offset_s)); }
    double displacement_rate(const SimTime& t, double offset_s = 0.0) const {
        return amplitude_m * angular_frequency() * std::cos(angle(t, offset_s));
    }
    double displacement_accel(const SimTime& t, double offset_s = 0.0) const {
        const double w = angular_frequency();
        return -amplitude_m * w * w * std::sin(angle(t, offset_s));
    }
    double angular_frequency() const { return 2.0 * M_PI * frequency_hz; }

    Pose pose(const SimTime& t, double offset_s = 0.0) const;

    // Velocity (m/s) of the material point of the component at world position x_w, time t + offset.
    Vec3 point_velocity(const Vec3& x_w, const SimTime& t, double offset_s = 0.0) const;

    // Acceleration (m/s2) of that material point (vibration only; rotation's centripetal part too).
    Vec3 point_acceleration(const Vec3& x_w, const SimTime& t, double offset_s = 0.0) const;

    // Largest surface speed (m/s) of this component, given its largest distance from the axis (m).
    double peak_surface_speed(double max_radius_m) const;

private:
    double angle(const SimTime& t, double offset_s) const { return 2.0 * M_PI * t.cycle_fraction(frequency_hz, offset_s) + phase_rad; }
};

}  // namespace peensim
