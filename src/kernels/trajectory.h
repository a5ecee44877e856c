// A shot centre's free flight between events: a ballistic parabola under constant gravity,
// evaluated exactly (equation (1) of the model), with its exact bounds over a time span.
#pragma once

#include <algorithm>
#include <cmath>

#include "common/vec.h"

namespace peensim {

struct Trajectory {
    Vec3 p0 = Vec3::Zero();  // m, centre at t0
    Vec3 v0 = Vec3::Zero();  // m/s, velocity at t0
    Vec3 g = Vec3::Zero();   // m/s^2, constant acceleration (gravity in the frame of the path)
    double t0 = 0.0;         // s, the time p0 and v0 refer to

    Vec3 position(double t) const {
        const double u = t - t0;
        return p0 + u * v0 + (0.5 * u * u) * g;
    }
    Vec3 velocity(double t) const { return v0 + (t - t0) * g; }

    // The same path, described from time t: keeps polynomial coefficients small when solving
    // near t, far from an old t0.
    Trajectory rebased(double t) const { return {position(t), velocity(t), g, t}; }

    // Exact axis-aligned bounds (m) of the centre over [ta, tb]: per axis a parabola, whose
    // extremes lie at the ends or at its apex.
    void bounds(double ta, double tb, Vec3& lo, Vec3& hi) const {
        const Vec3 pa = position(ta), pb = position(tb);
        lo = pa.cwiseMin(pb);
        hi = pa.cwiseMax(pb);
        for (int k = 0; k < 3; ++k) {
            if (g[k] == 0.0) continue;
            const double apex = t0 - v0[k] / g[k];  // where this velocity component vanishes
            if (apex > ta && apex < tb) {
                const double x = position(apex)[k];
                lo[k] = std::min(lo[k], x);
                hi[k] = std::max(hi[k], x);
            }
        }
    }

    // Largest speed (m/s) over [ta, tb]: the velocity is linear in t, so |v| is convex and
    // peaks at an end.
    double max_speed(double ta, double tb) const { return std::max(velocity(ta).norm(), velocity(tb).norm()); }
};

}  // namespace peensim
