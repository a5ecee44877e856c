#include "kernels/plate_release.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace peensim {

double seconds_to_release(double phase_rad, double eps, double angular_frequency_rad_per_s) {
    if (!(eps < 1.0)) return std::numeric_limits<double>::infinity();
    const double target = std::asin(std::max(-1.0, eps));
    double dphi = std::fmod(target - phase_rad, 2.0 * M_PI);
    if (dphi <= 0.0) dphi += 2.0 * M_PI;
    return dphi / angular_frequency_rad_per_s;
}

FlightState after_release(const FlightState& at_release, const Vec3& g_m_per_s2, double delay_s) {
    return {at_release.position_m + at_release.velocity_m_per_s * delay_s + 0.5 * g_m_per_s2 * delay_s * delay_s,
            at_release.velocity_m_per_s + g_m_per_s2 * delay_s};
}

}  // namespace peensim
