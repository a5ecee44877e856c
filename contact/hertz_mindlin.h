// Soft-sphere contact (reference sec. 4, the form LIGGGHTS and EDEM use): Hertz's normal force,
// Mindlin's no-slip tangential spring with Coulomb's cap, both damped from the coefficient of
// restitution. Pure functions of the pair's elastic constants and the contact's overlap and rates;
// the scheme that integrates them keeps the tangential spring as the contact's state.
#pragma once

#include <limits>

#include "common/vec.h"
#include "contact/soft_pair.h"

namespace peensim::contact {

struct ElasticMaterial {
    double youngs_modulus_pa = 0.0;  // Pa, E
    double poisson_ratio = 0.0;      // -, nu
};

// The constants of one contact pair (contact/soft_pair.h): SoftPair, family hertz_mindlin.
inline constexpr double kInfinite = std::numeric_limits<double>::infinity();

// beta of a coefficient of restitution e in (0, 1].
double hertz_beta(double restitution);

// A Hertz-Mindlin pair from its two materials, radii (m) and masses (kg); a wall has infinite
// radius and mass.
SoftPair hertz_pair(const ElasticMaterial& a, const ElasticMaterial& b, double radius_a_m, double radius_b_m, double mass_a_kg,
                    double mass_b_kg, double restitution, double friction);

// N, the normal force pushing the two apart at overlap delta (m, >= 0) closing at delta_rate
// (m/s, > 0 while approaching): 4/3 E* sqrt(R*) delta^3/2 - 2 sqrt(5/6) beta sqrt(S_n m*) delta_rate,
// S_n = 2 E* sqrt(R* delta). Not clamped: a damped contact pulls slightly at the very end of its
// restitution (the caller decides).
double hertz_normal_force(const SoftPair& p, double delta_m, double delta_rate_m_per_s);

// The normal force's two coefficients: hertz_normal_force = elastic delta^3/2 + damping delta^1/4
// delta_rate (elastic 4/3 E* sqrt(R*) in N/m^3/2; damping -2 sqrt(5/6) beta sqrt(2 E* sqrt(R*) m*)
// in N s/m^5/4, >= 0), for an integrator that needs the force's shape rather than its value.
struct HertzCoefficients {
    double elastic = 0.0;  // N/m^3/2
    double damping = 0.0;  // N s/m^5/4
};
HertzCoefficients hertz_coefficients(const SoftPair& p);

// N, the tangential force on body a (opposing the slip) and the spring's new extension (m), after
// dt (s) of tangential relative velocity v_t (m/s, of a against b, in the contact plane) at overlap
// delta (m) under normal force f_n (N): S_t = 8 G* sqrt(R* delta), F_t = -S_t s - 2 sqrt(5/6) beta
// sqrt(S_t m*) v_t, capped at friction f_n (the spring then shortened to match: a slider).
Vec3 mindlin_tangential_force(const SoftPair& p, double delta_m, double normal_force_n, const Vec3& v_t, double dt_s, Vec3& spring_m);
// The same with the spring's extension this step (slip_m, m) given apart from the slip velocity
// v_t (m/s) the damping acts on (an integrator may take them at different times of its step).
Vec3 mindlin_tangential_force(const SoftPair& p, double delta_m, double normal_force_n, const Vec3& v_t, const Vec3& slip_m,
                              Vec3& spring_m);

// J, the elastic energy of a Hertz contact at overlap delta (m): 8/15 E* sqrt(R*) delta^5/2.
double hertz_elastic_energy(const SoftPair& p, double delta_m);

// s, the duration of an elastic Hertz impact at approach speed v (m/s): 2.87 (m*^2 / (R* E*^2 v))^(1/5).
double hertz_contact_duration(const SoftPair& p, double v_m_per_s);

}  // namespace peensim::contact
