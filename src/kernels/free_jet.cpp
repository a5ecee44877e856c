#include "kernels/free_jet.h"

#include <cmath>

namespace peensim {

Vec3 FreeJet::velocity_at(const Vec3& p) const {
    const Vec3 offset = p - exit_m;
    const double s = offset.dot(axis);
    if (!(s > 0.0)) return Vec3::Zero();
    const double r = (offset - s * axis).norm();
    const double core_length = kDecayConstant * exit_diameter_m;  // m, s_c
    const double width = kSpreadingRate * s;                      // m, b (mixing layer) or r_h
    if (s < core_length) {
        const double core_radius = 0.5 * exit_diameter_m * (1.0 - s / core_length);
        if (r <= core_radius) return exit_speed_m_per_s * axis;
        const double x = (r - core_radius) / width;
        return exit_speed_m_per_s * std::exp(-std::log(2.0) * x * x) * axis;
    }
    const double x = r / width;
    return exit_speed_m_per_s * (core_length / s) * std::exp(-std::log(2.0) * x * x) * axis;
}

AirVelocityField::AirVelocityField(std::vector<FreeJet> jets) : jets_(std::move(jets)) {
    for (const FreeJet& j : jets_) max_speed_ += j.exit_speed_m_per_s;
}

Vec3 AirVelocityField::at(const Vec3& p) const {
    Vec3 u = Vec3::Zero();
    for (const FreeJet& j : jets_) u += j.velocity_at(p);
    return u;
}

}  // namespace peensim
