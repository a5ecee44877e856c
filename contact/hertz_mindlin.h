// Soft-sphere contact (reference sec. 4, the form LIGGGHTS and EDEM use): Hertz's normal force,
// Mindlin's no-slip tangential spring with Coulomb's cap, both damped from the coefficient of
// restitution. Pure functions of the pair's elastic constants and the contact's overlap and rates;
// the scheme that integrates them keeps the tangential spring as the contact's state.
#pragma once

#include <limits>

#include "common/vec.h"

namespace peensim::contact {

struct ElasticMaterial {
    double youngs_modulus_pa = 0.0;  // Pa, E
    double poisson_ratio = 0.0;      // -, nu
};

// The constants of one contact pair.
struct HertzPair {
    double E_star_pa = 0.0;  // Pa, 1/E* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j
    double G_star_pa = 0.0;  // Pa, 1/G* = 2 (2 - nu_i)(1 + nu_i)/E_i + 2 (2 - nu_j)(1 + nu_j)/E_j
    double R_star_m = 0.0;   // m, 1/R* = 1/R_i + 1/R_j (a wall: R_j infinite)
    double m_star_kg = 0.0;  // kg, 1/m* = 1/m_i + 1/m_j (a wall: m_j infinite)
    double beta = 0.0;       // -, ln e / sqrt(ln^2 e + pi^2): 0 for e = 1, negative below
    double friction = 0.0;   // -, Coulomb's coefficient
};

inline constexpr double kInfinite = std::numeric_limits<double>::infinity();

// beta of a coefficient of restitution e in (0, 1].
double hertz_beta(double restitution);

// A pair from its two materials, radii (m) and masses (kg); a wall has infinite radius and mass.
HertzPair hertz_pair(const ElasticMaterial& a, const ElasticMaterial& b, double radius_a_m, double radius_b_m, double mass_a_kg,
                     double mass_b_kg, double restitution, double friction);

// N, the normal force pushing the two apart at overlap delta (m, >= 0) closing at delta_rate
// (m/s, > 0 while approaching): 4/3 E* sqrt(R*) delta^3/2 - 2 sqrt(5/6) beta sqrt(S_n m*) delta_rate,
// S_n = 2 E* sqrt(R* delta). Not clamped: a damped contact pulls slightly at the very end of its
// restitution (the caller decides).
double hertz_normal_force(const HertzPair& p, double delta_m, double delta_rate_m_per_s);

// The normal force's two coefficients: hertz_normal_force = elastic delta^3/2 + damping delta^1/4
// delta_rate (elastic 4/3 E* sqrt(R*) in N/m^3/2; damping -2 sqrt(5/6) beta sqrt(2 E* sqrt(R*) m*)
// in N s/m^5/4, >= 0), for an integrator that needs the force's shape rather than its value.
struct HertzCoefficients {
    double elastic = 0.0;  // N/m^3/2
    double damping = 0.0;  // N s/m^5/4
};
HertzCoefficients hertz_coefficients(const HertzPair& p);

// N, the tangential force on body a (opposing the slip) and the spring's new extension (m), after
// dt (s) of tangential relative velocity v_t (m/s, of a against b, in the contact plane) at overlap
// delta (m) under normal force f_n (N): S_t = 8 G* sqrt(R* delta), F_t = -S_t s - 2 sqrt(5/6) beta
// sqrt(S_t m*) v_t, capped at friction f_n (the spring then shortened to match: a slider).
Vec3 mindlin_tangential_force(const HertzPair& p, double delta_m, double normal_force_n, const Vec3& v_t, double dt_s, Vec3& spring_m);
// The same with the spring's extension this step (slip_m, m) given apart from the slip velocity
// v_t (m/s) the damping acts on (an integrator may take them at different times of its step).
Vec3 mindlin_tangential_force(const HertzPair& p, double delta_m, double normal_force_n, const Vec3& v_t, const Vec3& slip_m,
                              Vec3& spring_m);

// s, the duration of an elastic Hertz impact at approach speed v (m/s): 2.87 (m*^2 / (R* E*^2 v))^(1/5).
double hertz_contact_duration(const HertzPair& p, double v_m_per_s);

}  // namespace peensim::contact
