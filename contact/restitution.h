// Velocity-dependent normal restitution, reference eq. 2:
//   C(V) = C0                     for V <  V0  (elastic regime)
//   C(V) = C0 * (V / V0)^(-1/4)   for V >= V0  (plastic regime)
#pragma once

#include <cmath>

namespace peensim::contact {

// approach_speed in m/s (>= 0); V0_m_per_s > 0. Returns the coefficient (dimensionless).
inline double normal_restitution(double approach_speed, double C0, double V0_m_per_s) {
    if (approach_speed < V0_m_per_s) return C0;
    // (V/V0)^(-1/4) = 1 / sqrt(sqrt(V/V0)): two square roots are faster and exact enough.
    return C0 / std::sqrt(std::sqrt(approach_speed / V0_m_per_s));
}

}  // namespace peensim::contact
