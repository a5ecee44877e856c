#include "kernels/box_entry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace peensim {

namespace {

// Roots in (ta, tb] of x_k(t) = bound for the parabola of axis k, appended to `out` (n counts them).
void axis_crossings(const Trajectory& path, int k, double bound, double ta, double tb, std::array<double, 16>& out, int& n) {
    // x(ta + u) = x0 + v u + h u^2 with everything taken at ta (small coefficients near the search).
    const double x0 = path.position(ta)[k] - bound, v = path.velocity(ta)[k], h = 0.5 * path.g[k];
    const auto keep = [&](double u) {
        if (u > 0.0 && ta + u <= tb && n < static_cast<int>(out.size())) out[static_cast<std::size_t>(n++)] = ta + u;
    };
    if (h == 0.0) {
        if (v != 0.0) keep(-x0 / v);
        return;
    }
    const double disc = v * v - 4.0 * h * x0;
    if (disc < 0.0) return;
    // The stable pair of roots (no cancellation).
    const double q = -0.5 * (v + std::copysign(std::sqrt(disc), v));
    keep(q / h);
    if (q != 0.0) keep(x0 / q);
}

// Inside the box on every axis, allowing for the rounding of a root (1e-12 of the box's size).
bool inside(const Vec3& p, const Vec3& lo, const Vec3& hi) {
    const Vec3 slack = 1e-12 * (hi - lo).cwiseAbs() + Vec3::Constant(1e-15);
    return ((p - lo).array() >= -slack.array()).all() && ((hi - p).array() >= -slack.array()).all();
}

}  // namespace

std::optional<double> first_time_inside_box(const Trajectory& path, const Vec3& lo, const Vec3& hi, double ta, double tb) {
    if (!(tb >= ta)) return std::nullopt;
    if (inside(path.position(ta), lo, hi)) return ta;
    std::array<double, 16> times{};
    int n = 0;
    for (int k = 0; k < 3; ++k) {
        axis_crossings(path, k, lo[k], ta, tb, times, n);
        axis_crossings(path, k, hi[k], ta, tb, times, n);
    }
    std::sort(times.begin(), times.begin() + n);
    for (int i = 0; i < n; ++i)
        if (inside(path.position(times[static_cast<std::size_t>(i)]), lo, hi)) return times[static_cast<std::size_t>(i)];
    return std::nullopt;
}

std::optional<double> first_time_outside_box(const Trajectory& path, const Vec3& lo, const Vec3& hi, double ta, double tb) {
    if (!(tb >= ta)) return std::nullopt;
    // Inside at ta, the centre first leaves where one coordinate first reaches a bound: per axis
    // x0 + v u + h u^2 = bound, the earliest root u > 0 (a hot path: every event-driven flight).
    const Vec3 p = path.position(ta), v = path.velocity(ta), h = 0.5 * path.g;
    double first = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
        for (const double bound : {lo[k], hi[k]}) {
            const double c = p[k] - bound;
            if ((bound == lo[k] && c < 0.0) || (bound == hi[k] && c > 0.0)) return ta;
            double u = std::numeric_limits<double>::infinity();
            if (h[k] == 0.0) {
                if (v[k] != 0.0 && -c / v[k] > 0.0) u = -c / v[k];
            } else {
                const double disc = v[k] * v[k] - 4.0 * h[k] * c;
                if (disc >= 0.0) {
                    const double q = -0.5 * (v[k] + std::copysign(std::sqrt(disc), v[k]));
                    for (const double r : {q / h[k], q != 0.0 ? c / q : std::numeric_limits<double>::infinity()})
                        if (r > 0.0) u = std::min(u, r);
                }
            }
            first = std::min(first, ta + u);
        }
    }
    if (!(first <= tb)) return std::nullopt;
    return first;
}

}  // namespace peensim
