#include "contact/hertz_mindlin_law.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "contact/impulse_laws.h"
#include "contact/restitution.h"

namespace peensim::contact {

namespace {

constexpr std::array kHertzMindlinParameters{
    LawParameter{"e", Dimension::dimensionless, "0.9", open_closed(0, 1), false,
                 "Coefficient of restitution: rebound over approach normal speed of one contact (the damping's beta)."},
    LawParameter{"f", Dimension::dimensionless, "0.1", at_least(0), false,
                 "Coulomb friction: caps the tangential force at f times the normal force (shot-shot too)."},
    LawParameter{"plastic_speed", Dimension::speed, "0", at_least(0), false,
                 "V0 of eq. 2: above this approach speed V the restitution is e (V/V0)^-1/4; 0: e at every speed."},
};

constexpr double kGripKeep = 5.0 / 7.0;  // -, tangential speed a solid sphere keeps once its contact point grips

HertzMindlinCoefficients coefficients(const ParameterValues& v) { return {v.scalar("e"), v.scalar("f"), v.scalar("plastic_speed")}; }

}  // namespace

double sphere_mass(double diameter_m, double density_kg_per_m3) {
    const double r = 0.5 * diameter_m;
    return density_kg_per_m3 * 4.0 / 3.0 * M_PI * r * r * r;
}

const ElasticMaterial& shot_elastic_for(std::string_view law, const std::optional<ElasticMaterial>& shot,
                                        const std::string& shot_material) {
    if (shot) return *shot;
    const std::string name(law);
    throw std::invalid_argument(shot_material.empty()
                                    ? "law '" + name +
                                          "' needs the shot's elastic constants: give shot.material, a material with "
                                          "youngs_modulus and poisson_ratio"
                                    : "law '" + name + "' needs the elastic constants of the shot's material '" + shot_material +
                                          "': add materials." + shot_material + ".youngs_modulus and .poisson_ratio");
}

const ElasticMaterial& surface_elastic_for(std::string_view law, const SurfacePair& pair) {
    if (pair.surface_elastic) return *pair.surface_elastic;
    throw std::invalid_argument("law '" + std::string(law) + "' needs the elastic constants of material '" + pair.material +
                                "': add materials." + pair.material + ".youngs_modulus and .poisson_ratio");
}

double HertzMindlinCoefficients::restitution(double v_m_per_s) const {
    return V0_m_per_s > 0.0 ? normal_restitution(v_m_per_s, e, V0_m_per_s) : e;
}

double rigid_tangential_keep(double vt_m_per_s, double vn_m_per_s, double e, double f) {
    if (!(vt_m_per_s > 0.0)) return 1.0;
    return std::max(kGripKeep, 1.0 - f * (1.0 + e) * vn_m_per_s / vt_m_per_s);
}

SurfaceContactResponse rigid_limit_impact(const SurfaceContactInput& in, const HertzMindlinCoefficients& k) {
    const Vec3 dV = in.v_shot - in.v_surface;
    const double vn = dV.dot(in.normal);
    const Vec3 vt = dV - vn * in.normal;
    SurfaceContactResponse out;
    out.v_shot = in.v_shot;
    out.vn_in = std::max(0.0, -vn);
    out.vt_in = vt.norm();
    if (!(vn < 0.0)) return out;
    const double e = k.restitution(-vn);
    out.v_shot = in.v_surface + rigid_tangential_keep(out.vt_in, -vn, e, k.f) * vt - e * vn * in.normal;
    out.vn_out = -e * vn;
    out.approaching = true;
    return out;
}

SurfaceContactResponse rigid_limit_sustain(const SurfaceContactInput& in, const HertzMindlinCoefficients& k) {
    return impulse_surface_sustain(in, k.f);
}

ShotShotResponse rigid_limit_respond(const ShotShotInput& in, const HertzMindlinCoefficients& k) {
    ShotShotResponse out{in.v_i, in.v_j, 0.0, false};
    const Vec3 rel = in.v_j - in.v_i;
    const double dV = rel.dot(in.normal);  // < 0 while approaching
    if (!(dV < 0.0)) return out;
    double e = 0.0;
    switch (in.mode) {
        case ShotShotMode::law: e = k.restitution(-dV); break;
        case ShotShotMode::sustained: e = 0.0; break;
        case ShotShotMode::collapse_guard: e = 1.0; break;
    }
    // Normal: the impulse changes each velocity in inverse proportion to its mass (eq. 3;
    // impulse_shares: a half each for equal masses, all of it to i against a held partner).
    // Tangential: the relative slip keeps rigid_tangential_keep of itself, shared the same way; a
    // sustained contact in a pile changes only the normal part (its friction is the substeps').
    const ImpulseShares share = impulse_shares(in);
    const Vec3 vt = rel - dV * in.normal;
    const double lost = in.mode == ShotShotMode::sustained ? 0.0 : 1.0 - rigid_tangential_keep(vt.norm(), -dV, e, k.f);
    const Vec3 exchange = (1.0 + e) * dV * in.normal + lost * vt;
    out.v_i = in.v_i + share.i * exchange;
    if (!in.j_held) out.v_j = in.v_j - share.j * exchange;
    out.vn_in = -dV;
    out.approaching = true;
    return out;
}

HertzMindlinSurfaceLaw::HertzMindlinSurfaceLaw(const HertzMindlinCoefficients& k, const ElasticMaterial& shot,
                                               const ElasticMaterial& surface, double shot_radius_m, double shot_mass_kg)
    : k_(k), elastic_(hertz_pair(shot, surface, shot_radius_m, kInfinite, shot_mass_kg, kInfinite, 1.0, k.f)) {}

SoftPair HertzMindlinSurfaceLaw::contact(double approach_speed_m_per_s) const {
    SoftPair p = elastic_;
    p.beta = hertz_beta(k_.restitution(approach_speed_m_per_s));
    return p;
}

SurfaceContactResponse HertzMindlinSurfaceLaw::impact(const SurfaceContactInput& in, std::span<double>) const {
    return rigid_limit_impact(in, k_);
}

SurfaceContactResponse HertzMindlinSurfaceLaw::sustain(const SurfaceContactInput& in, std::span<double>) const {
    return rigid_limit_sustain(in, k_);
}

HertzMindlinShotShotLaw::HertzMindlinShotShotLaw(const HertzMindlinCoefficients& k, const ElasticMaterial& shot, double shot_radius_m,
                                                 double shot_mass_kg)
    : k_(k), elastic_(hertz_pair(shot, shot, shot_radius_m, shot_radius_m, shot_mass_kg, shot_mass_kg, 1.0, k.f)) {}

SoftPair HertzMindlinShotShotLaw::contact(double approach_speed_m_per_s) const {
    SoftPair p = elastic_;
    p.beta = hertz_beta(k_.restitution(approach_speed_m_per_s));
    return p;
}

ShotShotResponse HertzMindlinShotShotLaw::respond(const ShotShotInput& in) const { return rigid_limit_respond(in, k_); }

std::span<const LawParameter> hertz_mindlin_parameters() { return kHertzMindlinParameters; }

std::shared_ptr<const SurfaceLaw> make_hertz_mindlin_surface(const ParameterValues& v, const SurfacePair& pair) {
    const ElasticMaterial& shot = shot_elastic_for("hertz-mindlin", pair.shot_elastic, pair.shot_material);
    const ElasticMaterial& surface = surface_elastic_for("hertz-mindlin", pair);
    return std::make_shared<HertzMindlinSurfaceLaw>(coefficients(v), shot, surface, 0.5 * pair.shot_diameter_m,
                                                    sphere_mass(pair.shot_diameter_m, pair.shot_density_kg_per_m3));
}

std::shared_ptr<const ShotShotLaw> make_hertz_mindlin_shot_shot(const ParameterValues& v, const ShotShotPair& pair) {
    const ElasticMaterial& shot = shot_elastic_for("hertz-mindlin", pair.shot_elastic, pair.shot_material);
    return std::make_shared<HertzMindlinShotShotLaw>(coefficients(v), shot, 0.5 * pair.shot_diameter_m,
                                                     sphere_mass(pair.shot_diameter_m, pair.shot_density_kg_per_m3));
}

}  // namespace peensim::contact
