#include "kernels/free_jet.h"

#include <algorithm>
#include <cmath>

namespace peensim {

Vec3 FreeJet::velocity_at(const Vec3& p) const {
    const Vec3 offset = p - exit_m;
    const double s = offset.dot(axis);
    if (!(s > 0.0)) return Vec3::Zero();
    const double r2 = (offset - s * axis).squaredNorm();
    const double centre = exit_speed_m_per_s * std::min(1.0, kDecayConstant * exit_diameter_m / s);
    const double half_width = std::max(0.5 * exit_diameter_m, kSpreadingRate * s);
    return centre * std::exp(-std::log(2.0) * r2 / (half_width * half_width)) * axis;
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
