#include "model/nozzle_source.h"

#include <cmath>

#include "common/random.h"
#include "common/units.h"
#include "model/emission_draw.h"
#include "model/shot_cavity.h"

namespace peensim {

NozzleSource::NozzleSource(const NozzleSpec& spec) : spec_(spec) {
    const Vec3& d = spec_.direction;
    // Any unit vector not along d, made perpendicular to it.
    const Vec3 helper = std::abs(d.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    e1_ = (helper - helper.dot(d) * d).normalized();
    e2_ = d.cross(e1_);
}

std::optional<Emission> NozzleSource::emission(std::uint64_t k, unsigned attempt) const {
    const std::optional<double> t = emission_time(spec_.plan, k);
    if (!t) return std::nullopt;
    Emission e;
    e.time_s = *t;
    Random rng(emission_stream(spec_.plan, k, attempt));
    const double r = spec_.exit_radius_m * std::sqrt(rng.uniform());  // uniform over the disc
    const double phi = 2.0 * M_PI * rng.uniform();
    e.position_m = spec_.position_m + r * (std::cos(phi) * e1_ + std::sin(phi) * e2_);
    // Uniform over the cone's spherical cap: cos(theta) uniform in [cos(spread), 1].
    const double cos_theta = 1.0 - rng.uniform() * (1.0 - std::cos(spec_.spread_rad));
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double psi = 2.0 * M_PI * rng.uniform();
    const Vec3 dir = cos_theta * spec_.direction + sin_theta * (std::cos(psi) * e1_ + std::sin(psi) * e2_);
    const double speed = spec_.speed_m_per_s * (1.0 + spec_.speed_spread * (2.0 * rng.uniform() - 1.0));
    e.velocity_m_per_s = speed * dir;
    e.size = emission_size(spec_.plan, k);
    return e;
}

SourceOutline NozzleSource::outline() const {
    SourceOutline o = outline_of(spec_.plan, "nozzle");
    o.fastest_speed_m_per_s = spec_.speed_m_per_s * (1.0 + spec_.speed_spread);
    o.start_lo_m = spec_.position_m - Vec3::Constant(spec_.exit_radius_m);
    o.start_hi_m = spec_.position_m + Vec3::Constant(spec_.exit_radius_m);
    o.jet = SourceJet{spec_.position_m, spec_.direction, spec_.speed_m_per_s};
    o.start_place = "exit";
    o.start_keys = "position, or target and distance";
    o.how = "at " + format_si(spec_.speed_m_per_s) + " m/s from its exit at " + mm_point(spec_.position_m);
    return o;
}

}  // namespace peensim
