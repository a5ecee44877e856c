// The kernel the per-area fields are smoothed with (surface_smoothing.h) and the coverage forecast
// estimates its local rates with (coverage_forecast.h): the quartic (biweight) kernel of support R
// times a facing factor, so that a point sees only the surface facing its way.
#pragma once

#include <cmath>

#include "common/vec.h"

namespace peensim {

// The quartic kernel's radial factor (1 - d^2/R^2)^2, 0 from R on (d2 = d^2, inv_r2 = 1 / R^2).
inline double quartic(double d2, double inv_r2) {
    const double u = 1.0 - d2 * inv_r2;
    return u > 0.0 ? u * u : 0.0;
}

// Its integral over a plane (m2): pi R^2 / 3.
inline double quartic_plane_integral(double radius_m) { return M_PI * radius_m * radius_m / 3.0; }

// Which of the 6 axis directions a unit normal faces most: 0..2 for +x, +y, +z, 3..5 for -x, -y, -z;
// -1 for a zero normal (a degenerate triangle). Bins keyed by it never hold both sides of a thin wall.
inline int facing_of(const Vec3& n) {
    if (!(n.squaredNorm() > 0.0)) return -1;
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(n[k]) > std::abs(n[axis])) axis = k;
    return n[axis] >= 0.0 ? axis : axis + 3;
}

}  // namespace peensim
