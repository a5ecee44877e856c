// Exact time of impact of a sphere on a ballistic path with a vibrating plane (the sonotrode
// face): the first moment the gap h(t) = n.(p(t) - q0 - a s(t)) - R, with s(t) = A sin(2 pi F t +
// phi), falls to zero or touches it. The gap is not a polynomial, so the search splits time where
// it can be decided exactly: outside the band where the centre's static plane distance is within
// |A n.a| of contact nothing can happen (one quadratic skips any number of periods); inside, knots
// where h'' changes sign cut each period into convex and concave pieces, each with at most one
// extreme of h, so every crossing is bracketed and every grazing minimum is located (by
// safeguarded Newton) and tested. Pure computation, no allocation.
#pragma once

#include "common/vec.h"
#include "kernels/toi_status.h"
#include "kernels/trajectory.h"

namespace peensim {

// A plane translating sinusoidally along a fixed axis: its points are x0 + a s(t) for every x0 of
// the plane through `point_m` normal to `normal`.
struct VibratingPlane {
    Vec3 point_m = Vec3::Zero();  // m, a point of the plane at rest (s = 0)
    Vec3 normal = Vec3::UnitZ();  // unit, out of the plate, towards the side the shots are on
    Vec3 axis = Vec3::UnitZ();    // unit, a: direction of the displacement
    double amplitude_m = 0.0;     // m, A
    // Hz, F. The frequency rather than w = 2 pi F: the phase at a large time is reduced from the
    // exact cycle count F t (see phase()), as the engine's Kinematics does, so both agree bit for bit.
    double frequency_hz = 0.0;
    double phase_rad = 0.0;  // rad, phi

    double angular_frequency() const;  // rad/s, w = 2 pi F

    // 2 pi F t + phi with the whole cycles of F t removed exactly (TwoProduct of F and t), in
    // [phi, phi + 2 pi): within a few 1e-16 rad of the exact phase of the double t, even at
    // 60 s and 20 kHz where the plain product w t (7.5e6 rad) is rounded by ~1e-9 rad.
    double phase(double t) const;
    double displacement(double t) const;  // m, s(t) along `axis`
    Vec3 velocity(double t) const;        // m/s, a A w cos(phase)
    Vec3 acceleration(double t) const;    // m/s^2, -a A w^2 sin(phase)
};

struct PlaneContact {
    double time = 0.0;                       // s
    Vec3 point = Vec3::Zero();               // m, the foot of the centre on the plane at `time`
    Vec3 normal = Vec3::UnitZ();             // unit, the plane's normal (towards the centre)
    Vec3 plate_velocity = Vec3::Zero();      // m/s, of the plane at `time`, for the contact law
    Vec3 plate_acceleration = Vec3::Zero();  // m/s^2, of the plane at `time` (whether a slow shot rides it)
};

// How much work one query did; optional, for tests and profiling.
struct PlaneToiWork {
    int windows = 0;     // stretches where the centre is within the band |A n.a| of the plane
    int pieces = 0;      // convex or concave pieces examined within them
    int iterations = 0;  // Newton or bisection steps (crossings and extremes)
};

// The first contact of a sphere of `radius` (m, > 0) moving on `path` with the side of `plane` its
// normal points to, in [t_begin, t_end] (s, absolute times: the plane's phase at t is phase(t)):
// - overlapping: the gap at t_begin is below -kStartTouchFraction * radius; `out` describes the
//   plane then (time = t_begin).
// - impact: the earliest time the gap falls to zero, or touches zero (a grazing double root, found
//   to within the rounding of the gap, ~1e-16 m), after t_begin. A sphere that starts touching
//   (|gap| within the tolerance) and approaching, or at rest relative to the plane and pulled in
//   (h'' < 0), is an impact at t_begin; one that starts touching and separating, as right after a
//   bounce, is not: the search skips the rise of the gap and reports the next return, which is the
//   first time the gap closes to zero again, or, if the gap never opened beyond that rounding
//   tolerance, the moment it starts closing (so a shot cannot slip through the plate unseen).
// - miss: neither.
// `work`, if given, is incremented by the work done.
ToiStatus vibrating_plane_toi(const Trajectory& path, double radius, const VibratingPlane& plane, double t_begin, double t_end,
                              PlaneContact& out, PlaneToiWork* work = nullptr);

// The gap h(t) (m) between the sphere and the plane, positive when apart: what the query solves for.
double vibrating_plane_gap(const Trajectory& path, double radius, const VibratingPlane& plane, double t);

}  // namespace peensim
