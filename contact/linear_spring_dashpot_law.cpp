#include "contact/linear_spring_dashpot_law.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace peensim::contact {

namespace {

constexpr std::array kLinearSpringDashpotParameters{
    LawParameter{"e", Dimension::dimensionless, "0.9", open_closed(0, 1), false,
                 "Coefficient of restitution: rebound over approach normal speed of one contact, at every speed (the dampers)."},
    LawParameter{"f", Dimension::dimensionless, "0.1", at_least(0), false,
                 "Coulomb friction: caps the tangential force at f times the normal force (shot-shot too)."},
    LawParameter{"characteristic_speed", Dimension::speed, "1 m/s", open_closed(0, 1e3), false,
                 "v_c, LIGGGHTS's characteristicVelocity: the normal stiffness is the linear spring's whose greatest overlap in "
                 "an impact at v_c is Hertz's (from the materials' E and nu). Contacts much faster than v_c go deeper than "
                 "Hertz's, slower ones less deep."},
    LawParameter{"tangential_ratio", Dimension::dimensionless, "1", open_closed(0, 1), false,
                 "k_t / k_n: 1 as LIGGGHTS's `model hooke`, 2/7 its ktToKn option."},
};

HertzMindlinCoefficients rigid_coefficients(const ParameterValues& v) { return {v.scalar("e"), v.scalar("f"), 0.0}; }

}  // namespace

SoftPair linear_spring_dashpot_pair(const ElasticMaterial& a, const ElasticMaterial& b, double radius_a_m, double radius_b_m,
                                    double mass_a_kg, double mass_b_kg, double restitution, double friction,
                                    double characteristic_speed_m_per_s, double tangential_ratio) {
    SoftPair p = hertz_pair(a, b, radius_a_m, radius_b_m, mass_a_kg, mass_b_kg, restitution, friction);
    p.family = SoftFamily::linear_spring_dashpot;
    const double root_r = std::sqrt(p.R_star_m), v = characteristic_speed_m_per_s;
    p.normal_stiffness_n_per_m =
        16.0 / 15.0 * root_r * p.E_star_pa * std::pow(15.0 * p.m_star_kg * v * v / (16.0 * root_r * p.E_star_pa), 0.2);
    p.tangential_stiffness_n_per_m = tangential_ratio * p.normal_stiffness_n_per_m;
    return p;
}

double linear_normal_damping(const SoftPair& p) { return -2.0 * p.beta * std::sqrt(p.normal_stiffness_n_per_m * p.m_star_kg); }

double linear_normal_force(const SoftPair& p, double delta_m, double delta_rate_m_per_s) {
    if (!(delta_m > 0.0)) return 0.0;  // apart: no spring, no damper
    return p.normal_stiffness_n_per_m * delta_m + linear_normal_damping(p) * delta_rate_m_per_s;
}

Vec3 linear_tangential_force(const SoftPair& p, double normal_force_n, const Vec3& v_t, const Vec3& slip_m, Vec3& spring_m) {
    return capped_spring_dashpot(p.tangential_stiffness_n_per_m, linear_normal_damping(p), p.friction, normal_force_n, v_t, slip_m,
                                 spring_m);
}

double linear_elastic_energy(const SoftPair& p, double delta_m) {
    const double d = std::max(0.0, delta_m);
    return 0.5 * p.normal_stiffness_n_per_m * d * d;
}

double linear_contact_duration(const SoftPair& p) {
    const double w0_2 = p.normal_stiffness_n_per_m / p.m_star_kg, half_rate = 0.5 * linear_normal_damping(p) / p.m_star_kg;
    return M_PI / std::sqrt(w0_2 - half_rate * half_rate);
}

SurfaceContactResponse LinearSpringDashpotSurfaceLaw::impact(const SurfaceContactInput& in, std::span<double>) const {
    return rigid_limit_impact(in, rigid_);
}

SurfaceContactResponse LinearSpringDashpotSurfaceLaw::sustain(const SurfaceContactInput& in, std::span<double>) const {
    return rigid_limit_sustain(in, rigid_);
}

ShotShotResponse LinearSpringDashpotShotShotLaw::respond(const ShotShotInput& in) const { return rigid_limit_respond(in, rigid_); }

std::span<const LawParameter> linear_spring_dashpot_parameters() { return kLinearSpringDashpotParameters; }

std::shared_ptr<const SurfaceLaw> make_linear_spring_dashpot_surface(const ParameterValues& v, const SurfacePair& pair) {
    const ElasticMaterial& shot = shot_elastic_for("linear-spring-dashpot", pair.shot_elastic, pair.shot_material);
    const ElasticMaterial& surface = surface_elastic_for("linear-spring-dashpot", pair);
    const HertzMindlinCoefficients k = rigid_coefficients(v);
    const SoftPair p = linear_spring_dashpot_pair(shot, surface, 0.5 * pair.shot_diameter_m, kInfinite,
                                                  sphere_mass(pair.shot_diameter_m, pair.shot_density_kg_per_m3), kInfinite, k.e, k.f,
                                                  v.scalar("characteristic_speed"), v.scalar("tangential_ratio"));
    return std::make_shared<LinearSpringDashpotSurfaceLaw>(p, k);
}

std::shared_ptr<const ShotShotLaw> make_linear_spring_dashpot_shot_shot(const ParameterValues& v, const ShotShotPair& pair) {
    const ElasticMaterial& shot = shot_elastic_for("linear-spring-dashpot", pair.shot_elastic, pair.shot_material);
    const HertzMindlinCoefficients k = rigid_coefficients(v);
    const double r = 0.5 * pair.shot_diameter_m, m = sphere_mass(pair.shot_diameter_m, pair.shot_density_kg_per_m3);
    const SoftPair p =
        linear_spring_dashpot_pair(shot, shot, r, r, m, m, k.e, k.f, v.scalar("characteristic_speed"), v.scalar("tangential_ratio"));
    return std::make_shared<LinearSpringDashpotShotShotLaw>(p, k);
}

}  // namespace peensim::contact
