#include "kernels/sphere_pair_toi.h"

#include <cmath>
#include <limits>

#include "kernels/polynomial_roots.h"

namespace peensim {

namespace {

// Spheres under different accelerations (one of them resting or riding a surface): the relative
// position dp + dv u + h u^2 makes |d|^2 - S^2 a quartic, whose first entering root is the
// contact. Called once the start is known to be clear (gap above the touch band).
// `touching`: the spheres touch at t_begin without approaching; the quartic then has its root
// there, divided out, and the first entering root of the cubic left is the next contact (at
// t_begin itself if the acceleration presses them together: a shot lying on a resting one).
ToiStatus accelerated_pair_toi(const Vec3& dp, const Vec3& dv, const Vec3& h, double S, double t_begin, double t_end, bool touching,
                               PairContact& out) {
    Polynomial p;
    if (touching) {
        p.degree = 3;
        p.c = {2.0 * dp.dot(dv), dv.dot(dv) + 2.0 * dp.dot(h), 2.0 * dv.dot(h), h.dot(h), 0.0};
    } else {
        p.degree = 4;
        p.c = {(dp.norm() - S) * (dp.norm() + S), 2.0 * dp.dot(dv), dv.dot(dv) + 2.0 * dp.dot(h), 2.0 * dv.dot(h), h.dot(h)};
    }
    PolynomialRoot root;
    if (!first_root_in(p, 0.0, t_end - t_begin, root, RootFilter::entering)) return ToiStatus::miss;
    out.time = t_begin + root.t;
    const Vec3 d = dp + root.t * (dv + root.t * h);
    const double dn = d.norm();
    out.normal = dn > 0.0 ? Vec3(d / dn) : Vec3(Vec3::UnitZ());
    return ToiStatus::impact;
}

}  // namespace

ToiStatus sphere_pair_toi(const Trajectory& p1, double r1, const Trajectory& p2, double r2, double t_begin, double t_end,
                          PairContact& out) {
    if (!(t_end >= t_begin)) return ToiStatus::miss;
    constexpr double kEps = std::numeric_limits<double>::epsilon();
    const double S = r1 + r2;
    // Relative motion from t_begin: dp + dv u, u = t - t_begin (gravity cancels).
    const Vec3 dp = p2.position(t_begin) - p1.position(t_begin);
    const Vec3 dv = p2.velocity(t_begin) - p1.velocity(t_begin);
    const double dist = dp.norm();
    const double b = dp.dot(dv);                   // half the rate of change of |dp|^2
    if (dist < S * (1.0 + kStartTouchFraction)) {  // touching or overlapping: see toi_status.h
        out.time = t_begin;
        out.normal = dist > 0.0 ? Vec3(dp / dist) : Vec3(Vec3::UnitZ());
        if (dist < S * (1.0 - kStartTouchFraction)) return ToiStatus::overlapping;
        if (b < 0.0) return ToiStatus::impact;
        if (p2.g == p1.g) return ToiStatus::miss;  // separating on a straight line: never again
        return accelerated_pair_toi(dp, dv, 0.5 * (p2.g - p1.g), S, t_begin, t_end, /*touching=*/true, out);
    }
    if (p2.g != p1.g) return accelerated_pair_toi(dp, dv, 0.5 * (p2.g - p1.g), S, t_begin, t_end, /*touching=*/false, out);
    if (b >= 0.0) return ToiStatus::miss;  // not closing: the gap only grows
    const double a = dv.squaredNorm();
    const double c = (dist - S) * (dist + S);  // >= 0: |dp|^2 - S^2 without cancelling
    double disc = b * b - a * c;
    // A tangent pass leaves disc = 0 up to the rounding of its two products: a graze at the
    // closest approach. (Taking a rounding-level disc at face value would move the time by
    // sqrt(eps) relative: the root of a near-double root is that ill-conditioned.)
    if (std::fabs(disc) <= 8.0 * kEps * (b * b + a * c)) disc = 0.0;
    if (disc < 0.0) return ToiStatus::miss;
    // The smaller root (-b - sqrt(disc)) / a, written without cancellation (b < 0).
    const double u = c / (-b + std::sqrt(disc));
    if (u > t_end - t_begin) return ToiStatus::miss;
    out.time = t_begin + u;
    const Vec3 d = dp + u * dv;
    const double dn = d.norm();
    out.normal = dn > 0.0 ? Vec3(d / dn) : Vec3(Vec3::UnitZ());
    return ToiStatus::impact;
}

}  // namespace peensim
