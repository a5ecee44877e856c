#include "kernels/swept_sphere_box.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "common/float_limits.h"

namespace peensim {

namespace {

// The box grows by this fraction of the radius beyond the radius itself, so that a root found an
// ulp late, or a box corner rounded inwards, can never cut off a contact.
constexpr double kRelativePad = 1e-6;

struct Interval {
    double lo, hi;
};

// Real roots r1 <= r2 of h u^2 + v u + c (h != 0), without cancellation; false if none.
bool quadratic_roots(double h, double v, double c, double& r1, double& r2) {
    const double disc = v * v - 4.0 * h * c;
    if (disc < 0.0) return false;
    const double q = -0.5 * (v + std::copysign(std::sqrt(disc), v));
    if (q == 0.0) {  // v == 0 and c == 0: a double root at 0
        r1 = r2 = 0.0;
        return true;
    }
    r1 = q / h;
    r2 = c / q;
    if (r1 > r2) std::swap(r1, r2);
    return true;
}

// The times u in [0, T] at which x0 + v u + h u^2 lies in [L, H]: at most two intervals, in order.
int axis_set(double x0, double v, double h, double L, double H, double T, Interval* out) {
    int n = 0;
    auto add = [&](double a, double b) {
        a = std::max(a, 0.0);
        b = std::min(b, T);
        if (a <= b) out[n++] = {a, b};
    };
    if (h == 0.0) {
        if (v == 0.0) {
            if (x0 >= L && x0 <= H) add(0.0, T);
            return n;
        }
        double ta = (L - x0) / v, tb = (H - x0) / v;
        if (ta > tb) std::swap(ta, tb);
        add(ta, tb);
        return n;
    }
    if (h < 0.0) {  // mirror x -> -x so the parabola opens upwards
        x0 = -x0;
        v = -v;
        h = -h;
        const double lower = -H;
        H = -L;
        L = lower;
    }
    // Convex: x <= H between the roots of x = H (never if none); x >= L outside the roots of x = L.
    double a1, a2, b1, b2;
    if (!quadratic_roots(h, v, x0 - H, a1, a2)) return 0;
    if (quadratic_roots(h, v, x0 - L, b1, b2)) {
        add(a1, b1);
        add(b2, a2);
    } else {
        add(a1, a2);
    }
    return n;
}

// A and B sorted disjoint intervals; C receives their intersection (at most na + nb - 1).
int intersect(const Interval* A, int na, const Interval* B, int nb, Interval* C) {
    int i = 0, j = 0, n = 0;
    while (i < na && j < nb) {
        const double lo = std::max(A[i].lo, B[j].lo), hi = std::min(A[i].hi, B[j].hi);
        if (lo <= hi) C[n++] = {lo, hi};
        if (A[i].hi < B[j].hi)
            ++i;
        else
            ++j;
    }
    return n;
}

}  // namespace

SweptSphere::SweptSphere(const Trajectory& path, double radius, double t_begin, double t_end)
    : x0_(path.position(t_begin)),
      v_(path.velocity(t_begin)),
      h_(0.5 * path.g),
      radius_(radius),
      t_begin_(t_begin),
      duration_(std::max(0.0, t_end - t_begin)) {
    const double T = duration_;
    const double extent = x0_.norm() + v_.norm() * T + h_.norm() * T * T;
    pad_ = kRelativePad * radius + 16.0 * kEps * extent;
    shorten(t_end);
}

void SweptSphere::classify_axes() {
    const double T = duration_;
    for (int k = 0; k < 3; ++k) {
        AxisMotion& a = axis_[k];
        a.sign = h_[k] < 0.0 ? -1.0 : 1.0;
        a.x0 = a.sign * x0_[k];
        a.v = a.sign * v_[k];
        a.h = a.sign * h_[k];
        // A tiny h (gravity's rounding residue on a tilted frame) would make 1 / (2 h) blow up;
        // dropping it moves x by at most h T^2, which the pad covers.
        a.linear = a.h * T * T <= 0.25 * pad_;
        a.inv_v = a.v != 0.0 ? 1.0 / a.v : 0.0;
        a.inv_2h = a.linear ? 0.0 : 0.5 / a.h;
    }
}

void SweptSphere::shorten(double t_end) {
    duration_ = std::clamp(t_end - t_begin_, 0.0, duration_);
    const Trajectory local{x0_, v_, 2.0 * h_, 0.0};
    local.bounds(0.0, duration_, reach_lo_, reach_hi_);
    const Vec3 grow = Vec3::Constant(radius_ + pad_);
    reach_lo_ -= grow;
    reach_hi_ += grow;
    classify_axes();
}

namespace {

// The times u in [0, T] at which the axis lies in [L, H]: at most two intervals, in order.
// Closed forms with the precomputed reciprocals: the cancellation in -v + sqrt(disc) costs
// ~eps |v| / (2 h) in time, far inside the pad.
template <typename Axis>
int axis_times(const Axis& a, double L, double H, double T, Interval* out) {
    if (a.sign < 0.0) {
        const double lower = -H;
        H = -L;
        L = lower;
    }
    int n = 0;
    auto add = [&](double lo, double hi) {
        lo = std::max(lo, 0.0);
        hi = std::min(hi, T);
        if (lo <= hi) out[n++] = {lo, hi};
    };
    if (a.linear) {
        if (a.v == 0.0) {
            if (a.x0 >= L && a.x0 <= H) add(0.0, T);
            return n;
        }
        double ta = (L - a.x0) * a.inv_v, tb = (H - a.x0) * a.inv_v;
        if (ta > tb) std::swap(ta, tb);
        add(ta, tb);
        return n;
    }
    // Convex: below H between the roots of x = H (never if none), above L outside those of x = L.
    const double disc_h = a.v * a.v - 4.0 * a.h * (a.x0 - H);
    if (disc_h < 0.0) return 0;
    const double root_h = std::sqrt(disc_h);
    const double a1 = (-a.v - root_h) * a.inv_2h, a2 = (-a.v + root_h) * a.inv_2h;
    const double disc_l = a.v * a.v - 4.0 * a.h * (a.x0 - L);
    if (disc_l < 0.0) {
        add(a1, a2);
        return n;
    }
    const double root_l = std::sqrt(disc_l);
    add(a1, (-a.v - root_l) * a.inv_2h);
    add((-a.v + root_l) * a.inv_2h, a2);
    return n;
}

}  // namespace

bool SweptSphere::span(const Vec3& lo, const Vec3& hi, TimeSpan& out) const {
    for (int k = 0; k < 3; ++k)
        if (hi[k] < reach_lo_[k] || lo[k] > reach_hi_[k]) return false;
    const double grow = radius_ + pad_;
    Interval sets[3][2];
    int counts[3];
    bool single = true;
    for (int k = 0; k < 3; ++k) {
        counts[k] = axis_times(axis_[k], lo[k] - grow, hi[k] + grow, duration_, sets[k]);
        if (counts[k] == 0) return false;
        single = single && counts[k] == 1;
    }
    if (single) {  // the usual case: one interval per axis
        const double first = std::max({sets[0][0].lo, sets[1][0].lo, sets[2][0].lo});
        const double last = std::min({sets[0][0].hi, sets[1][0].hi, sets[2][0].hi});
        if (first > last) return false;
        out.first = t_begin_ + first;
        out.last = t_begin_ + last;
        return true;
    }
    Interval acc[4], next[4];
    int na = counts[0];
    std::copy(sets[0], sets[0] + na, acc);
    for (int k = 1; k < 3 && na > 0; ++k) {
        na = intersect(acc, na, sets[k], counts[k], next);
        std::copy(next, next + na, acc);
    }
    if (na == 0) return false;
    out.first = t_begin_ + acc[0].lo;
    out.last = t_begin_ + acc[na - 1].hi;
    return true;
}

bool SweptSphere::slab_span(const Vec3& n, double lo, double hi, TimeSpan& out) const {
    const double grow = radius_ + pad_;
    Interval set[2];
    const int count = axis_set(n.dot(x0_), n.dot(v_), n.dot(h_), lo - grow, hi + grow, duration_, set);
    if (count == 0) return false;
    out.first = t_begin_ + set[0].lo;
    out.last = t_begin_ + set[count - 1].hi;
    return true;
}

}  // namespace peensim
