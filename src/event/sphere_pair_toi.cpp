#include "event/sphere_pair_toi.h"

#include <cassert>
#include <cmath>
#include <limits>

namespace peensim {

ToiStatus sphere_pair_toi(const Trajectory& p1, double r1, const Trajectory& p2, double r2, double t_begin,
                          double t_end, PairContact& out) {
    assert(p1.g == p2.g);
    if (!(t_end >= t_begin)) return ToiStatus::miss;
    constexpr double kEps = std::numeric_limits<double>::epsilon();
    const double S = r1 + r2;
    // Relative motion from t_begin: dp + dv u, u = t - t_begin (gravity cancels).
    const Vec3 dp = p2.position(t_begin) - p1.position(t_begin);
    const Vec3 dv = p2.velocity(t_begin) - p1.velocity(t_begin);
    const double dist = dp.norm();
    const double b = dp.dot(dv);  // half the rate of change of |dp|^2
    if (dist < S * (1.0 + kStartTouchFraction)) {  // touching or overlapping: see toi_status.h
        out.time = t_begin;
        out.normal = dist > 0.0 ? Vec3(dp / dist) : Vec3(Vec3::UnitZ());
        if (dist < S * (1.0 - kStartTouchFraction)) return ToiStatus::overlapping;
        return b < 0.0 ? ToiStatus::impact : ToiStatus::miss;
    }
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
