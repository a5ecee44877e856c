#include "contact/rebound_scatter.h"

#include <bit>
#include <cmath>

#include "common/random.h"

namespace peensim::contact {

namespace {

class ScatteredLaw final : public SurfaceLaw {
public:
    ScatteredLaw(std::shared_ptr<const SurfaceLaw> law, const ReboundScatter& scatter) : law_(std::move(law)), scatter_(scatter) {}

    std::string_view name() const override { return law_->name(); }
    int state_per_triangle() const override { return law_->state_per_triangle(); }
    int state_per_contact() const override { return law_->state_per_contact(); }
    std::string describe_state(std::span<const double> state) const override { return law_->describe_state(state); }
    const SoftLaw* soft() const override { return law_->soft(); }
    SurfaceContactResponse sustain(const SurfaceContactInput& in, std::span<double> state) const override {
        return law_->sustain(in, state);
    }

    SurfaceContactResponse impact(const SurfaceContactInput& in, std::span<double> state) const override {
        SurfaceContactResponse r = law_->impact(in, state);
        if (!in.impact || !r.approaching) return r;
        const Vec3 air = scatter_.air_velocity ? scatter_.air_velocity(in.point_world) : Vec3(Vec3::Zero());
        if (!scatters(scatter_, (in.v_shot - in.v_surface).norm(), (air - r.v_shot).norm(), 2.0 * in.shot_radius_m)) return r;
        // The contact's own generator: seed, shot, triangle and the time's bits mixed (SplitMix64
        // seeding spreads neighbouring values).
        Random rng(scatter_.seed * 0x9e3779b97f4a7c15ull ^ (static_cast<std::uint64_t>(in.shot + 1) << 32) ^
                   static_cast<std::uint64_t>(in.triangle + 1) ^ std::bit_cast<std::uint64_t>(in.time_s));
        const double angle = scatter_.spread_rad * rng.uniform();
        const double psi = 2.0 * M_PI * rng.uniform();
        const Vec3& n = in.normal;
        const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
        const Vec3 e1 = (helper - helper.dot(n) * n).normalized(), e2 = n.cross(e1);
        const Vec3 u = deflected(r.v_shot - in.v_surface, n, std::cos(psi) * e1 + std::sin(psi) * e2, angle);
        r.v_shot = in.v_surface + u;
        r.vn_out = u.dot(n);
        return r;
    }

private:
    std::shared_ptr<const SurfaceLaw> law_;
    ReboundScatter scatter_;
};

}  // namespace

bool scatters(const ReboundScatter& s, double impact_speed_m_per_s, double rebound_against_air_m_per_s, double diameter_m) {
    const double reynolds = s.air_density_kg_per_m3 * rebound_against_air_m_per_s * diameter_m / s.air_viscosity_pa_s;
    return impact_speed_m_per_s >= s.min_speed_m_per_s && reynolds >= s.min_reynolds;
}

Vec3 deflected(const Vec3& u, const Vec3& n, const Vec3& t, double angle_rad) {
    const double speed = u.norm();
    if (!(speed > 0.0)) return u;
    // Turn the direction about the axis n x t' (t' = t less its part along u) by the angle, which
    // moves it towards t; kept above the surface (u . n > 0 stays so for angles below the rebound's
    // elevation; a larger turn is stopped at a grazing 1 % of the speed along n).
    const Vec3 d = u / speed;
    Vec3 side = t - t.dot(d) * d;
    if (side.squaredNorm() < 1e-24) return u;
    side.normalize();
    Vec3 turned = std::cos(angle_rad) * d + std::sin(angle_rad) * side;
    const double along_n = turned.dot(n), floor = 0.01;
    if (along_n < floor) {
        const Vec3 in_plane = turned - along_n * n;
        turned = floor * n + std::sqrt(1.0 - floor * floor) * in_plane.normalized();
    }
    return speed * turned;
}

std::shared_ptr<const SurfaceLaw> with_rebound_scatter(std::shared_ptr<const SurfaceLaw> law, const ReboundScatter& scatter) {
    return std::make_shared<ScatteredLaw>(std::move(law), scatter);
}

}  // namespace peensim::contact
