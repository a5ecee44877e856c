// When a sphere on a ballistic path can touch anything inside an axis-aligned box: the times its
// centre lies in the box grown by the radius on every axis, from per-axis quadratics. The BVH walk
// orders nodes by the first of these times and bounds each leaf's exact search by them. Always
// conservative: the box is grown by a further pad, so rounding can only widen the span.
#pragma once

#include "common/vec.h"
#include "kernels/trajectory.h"

namespace peensim {

struct TimeSpan {
    double first = 0.0;  // s
    double last = 0.0;   // s
};

class SweptSphere {
public:
    // A sphere of `radius` (m, > 0) on `path` over [t_begin, t_end] (s).
    SweptSphere(const Trajectory& path, double radius, double t_begin, double t_end);

    // Ends the sweep earlier (s, in [t_begin, current end]): after a hit nothing later matters.
    void shorten(double t_end);
    double t_begin() const { return t_begin_; }
    double t_end() const { return t_begin_ + duration_; }

    // The first and last time in [t_begin, t_end] at which the centre is within radius (plus the
    // pad) of the box [lo, hi] (m) along every axis; false if never. Between them the centre may
    // leave and re-enter (a parabola can cross a slab twice).
    bool span(const Vec3& lo, const Vec3& hi, TimeSpan& out) const;

    // The same for the slab lo <= n . x <= hi (n a unit vector, lo and hi in m), e.g. a
    // triangle's plane (lo = hi): the first and last time the centre is within radius (plus the
    // pad) of it.
    bool slab_span(const Vec3& n, double lo, double hi, TimeSpan& out) const;

    // The centre's bounds over the sweep grown by the radius and the pad (m): nothing outside
    // this box is within reach; span() tests every box against it first.
    const Vec3& reach_lo() const { return reach_lo_; }
    const Vec3& reach_hi() const { return reach_hi_; }

    // Added to the radius on every side (m): 1e-6 R plus rounding of the coordinates.
    double pad() const { return pad_; }

private:
    // One axis of the centre's motion, x0 + v u + h u^2 (u = t - t_begin), mirrored if need be
    // so that h >= 0; `linear` when h u^2 stays below a quarter of the pad over the sweep.
    struct AxisMotion {
        double x0 = 0.0, v = 0.0, h = 0.0;  // m, m/s, m/s^2
        double sign = 1.0;                  // -1: stored mirrored (x -> -x)
        bool linear = true;
        double inv_v = 0.0;   // s/m, 1 / v for a linear axis with v != 0
        double inv_2h = 0.0;  // s^2/m, 1 / (2 h) for a parabolic one
    };
    void classify_axes();

    Vec3 x0_, v_, h_;  // centre at t_begin (m), velocity (m/s), g / 2 (m/s^2)
    AxisMotion axis_[3];
    double radius_ = 0.0;       // m
    double pad_ = 0.0;          // m
    double t_begin_ = 0.0;      // s
    double duration_ = 0.0;     // s
    Vec3 reach_lo_, reach_hi_;  // m, the centre's bounds over the sweep grown by radius + pad
};

}  // namespace peensim
