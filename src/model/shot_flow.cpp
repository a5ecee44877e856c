#include "model/shot_flow.h"

#include <cmath>

#include "common/random.h"
#include "kernels/box_entry.h"
#include "scene/shot_mix.h"

namespace peensim {

NozzleSource::NozzleSource(const NozzleSpec& spec) : spec_(spec) {
    const Vec3& d = spec_.direction;
    // Any unit vector not along d, made perpendicular to it.
    const Vec3 helper = std::abs(d.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    e1_ = (helper - helper.dot(d) * d).normalized();
    e2_ = d.cross(e1_);
}

std::uint64_t NozzleSource::emission_stream(std::uint64_t k, unsigned attempt) const {
    return spec_.seed * 0x9e3779b97f4a7c15ull ^ (static_cast<std::uint64_t>(spec_.index + 1) << 48) ^
           (static_cast<std::uint64_t>(attempt) << 40) ^ k;
}

std::optional<Emission> NozzleSource::emission(std::uint64_t k, unsigned attempt) const {
    Emission e;
    e.time_s = spec_.start_s + static_cast<double>(k) / spec_.rate_per_s;
    if (!(e.time_s < spec_.stop_s)) return std::nullopt;
    // Emission k's own generator (emission_stream): no generator state is carried between emissions.
    Random rng(emission_stream(k, attempt));
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
    // The size: a stream of its own (attempt 255, never a redraw's), so a redraw moves the shot but
    // keeps its size, and a scene of one size draws nothing.
    if (spec_.size_count_fraction.size() > 1) {
        Random size_rng(emission_stream(k, kSizeStream));
        e.size = size_for_draw(spec_.size_count_fraction, size_rng.uniform());
    }
    return e;
}

bool BoxSink::contains(const Vec3& p) const {
    const bool in = (p.array() >= lo_.array()).all() && (p.array() <= hi_.array()).all();
    return side_ == Side::inside ? in : !in;
}

std::optional<double> BoxSink::first_entry(const Trajectory& path, double ta, double tb) const {
    return side_ == Side::inside ? first_time_inside_box(path, lo_, hi_, ta, tb) : first_time_outside_box(path, lo_, hi_, ta, tb);
}

}  // namespace peensim
