#include "contact/hertz_mindlin.h"

#include <algorithm>
#include <cmath>

namespace peensim::contact {

namespace {
const double kDampingFactor = 2.0 * std::sqrt(5.0 / 6.0);  // -, of the damping terms

// 1/x of a pair's two halves, an infinite half contributing nothing.
double harmonic(double a_inverse, double b_inverse) { return 1.0 / (a_inverse + b_inverse); }
double inverse(double x) { return std::isinf(x) ? 0.0 : 1.0 / x; }
}  // namespace

double hertz_beta(double restitution) {
    const double l = std::log(restitution);
    return l / std::sqrt(l * l + M_PI * M_PI);
}

SoftPair hertz_pair(const ElasticMaterial& a, const ElasticMaterial& b, double radius_a_m, double radius_b_m, double mass_a_kg,
                    double mass_b_kg, double restitution, double friction) {
    SoftPair p;
    p.family = SoftFamily::hertz_mindlin;
    const auto e_part = [](const ElasticMaterial& m) { return (1.0 - m.poisson_ratio * m.poisson_ratio) / m.youngs_modulus_pa; };
    const auto g_part = [](const ElasticMaterial& m) {
        return 2.0 * (2.0 - m.poisson_ratio) * (1.0 + m.poisson_ratio) / m.youngs_modulus_pa;
    };
    p.E_star_pa = harmonic(e_part(a), e_part(b));
    p.G_star_pa = harmonic(g_part(a), g_part(b));
    p.R_star_m = harmonic(inverse(radius_a_m), inverse(radius_b_m));
    p.m_star_kg = harmonic(inverse(mass_a_kg), inverse(mass_b_kg));
    p.beta = hertz_beta(restitution);
    p.friction = friction;
    return p;
}

double hertz_normal_force(const SoftPair& p, double delta_m, double delta_rate_m_per_s) {
    const double d = std::max(0.0, delta_m);
    const double root = std::sqrt(p.R_star_m * d);
    const double s_n = 2.0 * p.E_star_pa * root;  // N/m, normal stiffness
    return 4.0 / 3.0 * p.E_star_pa * root * d - kDampingFactor * p.beta * std::sqrt(s_n * p.m_star_kg) * delta_rate_m_per_s;
}

HertzCoefficients hertz_coefficients(const SoftPair& p) {
    const double root_r = std::sqrt(p.R_star_m);
    return {4.0 / 3.0 * p.E_star_pa * root_r, -kDampingFactor * p.beta * std::sqrt(2.0 * p.E_star_pa * root_r * p.m_star_kg)};
}

Vec3 mindlin_tangential_force(const SoftPair& p, double delta_m, double normal_force_n, const Vec3& v_t, double dt_s, Vec3& spring_m) {
    return mindlin_tangential_force(p, delta_m, normal_force_n, v_t, Vec3(v_t * dt_s), spring_m);
}

Vec3 mindlin_tangential_force(const SoftPair& p, double delta_m, double normal_force_n, const Vec3& v_t, const Vec3& slip_m,
                              Vec3& spring_m) {
    const double s_t = 8.0 * p.G_star_pa * std::sqrt(p.R_star_m * std::max(0.0, delta_m));  // N/m
    const double c_t = -kDampingFactor * p.beta * std::sqrt(s_t * p.m_star_kg);             // N s/m, beta <= 0: opposes v_t
    return capped_spring_dashpot(s_t, c_t, p.friction, normal_force_n, v_t, slip_m, spring_m);
}

double hertz_elastic_energy(const SoftPair& p, double delta_m) {
    const double d = std::max(0.0, delta_m);
    return 8.0 / 15.0 * p.E_star_pa * std::sqrt(p.R_star_m) * d * d * std::sqrt(d);
}

double hertz_contact_duration(const SoftPair& p, double v_m_per_s) {
    return 2.87 * std::pow(p.m_star_kg * p.m_star_kg / (p.R_star_m * p.E_star_pa * p.E_star_pa * v_m_per_s), 0.2);
}

}  // namespace peensim::contact
