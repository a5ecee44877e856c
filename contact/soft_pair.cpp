#include "contact/soft_pair.h"

#include <algorithm>

#include "contact/hertz_mindlin.h"
#include "contact/linear_spring_dashpot_law.h"

namespace peensim::contact {

SoftForceShape soft_force_shape(const SoftPair& p) {
    switch (p.family) {
        case SoftFamily::hertz_mindlin: {
            const HertzCoefficients c = hertz_coefficients(p);
            return {c.elastic, 1.5, c.damping, 0.25};
        }
        case SoftFamily::linear_spring_dashpot: return {p.normal_stiffness_n_per_m, 1.0, linear_normal_damping(p), 0.0};
    }
    return {};
}

double soft_normal_force(const SoftPair& p, double delta_m, double delta_rate_m_per_s) {
    switch (p.family) {
        case SoftFamily::hertz_mindlin: return hertz_normal_force(p, delta_m, delta_rate_m_per_s);
        case SoftFamily::linear_spring_dashpot: return linear_normal_force(p, delta_m, delta_rate_m_per_s);
    }
    return 0.0;
}

namespace {

Vec3 spring_of(const SoftContactState& state) { return {state[0], state[1], state[2]}; }
void store_spring(SoftContactState& state, const Vec3& spring_m) { state = {spring_m.x(), spring_m.y(), spring_m.z()}; }

}  // namespace

void soft_turn_state(const SoftPair& /*p*/, SoftContactState& state, const Vec3& n) {
    const Vec3 spring = spring_of(state);
    const double length = spring.norm();
    if (!(length > 0.0)) return store_spring(state, Vec3::Zero());
    const Vec3 s = spring - spring.dot(n) * n;
    const double in_plane = s.norm();
    store_spring(state, in_plane > 0.0 ? Vec3(s * (length / in_plane)) : Vec3(Vec3::Zero()));
}

Vec3 soft_tangential_force(const SoftPair& p, double delta_m, double normal_force_n, const Vec3& v_t, const Vec3& slip_m,
                           SoftContactState& state) {
    Vec3 spring = spring_of(state);
    Vec3 force = Vec3::Zero();
    switch (p.family) {
        case SoftFamily::hertz_mindlin: force = mindlin_tangential_force(p, delta_m, normal_force_n, v_t, slip_m, spring); break;
        case SoftFamily::linear_spring_dashpot: force = linear_tangential_force(p, normal_force_n, v_t, slip_m, spring); break;
    }
    store_spring(state, spring);
    return force;
}

double soft_elastic_energy(const SoftPair& p, double delta_m) {
    switch (p.family) {
        case SoftFamily::hertz_mindlin: return hertz_elastic_energy(p, delta_m);
        case SoftFamily::linear_spring_dashpot: return linear_elastic_energy(p, delta_m);
    }
    return 0.0;
}

double soft_contact_duration(const SoftPair& p, double v_m_per_s) {
    switch (p.family) {
        case SoftFamily::hertz_mindlin: return hertz_contact_duration(p, v_m_per_s);
        case SoftFamily::linear_spring_dashpot: return linear_contact_duration(p);
    }
    return 0.0;
}

Vec3 capped_spring_dashpot(double s_t_n_per_m, double c_t_n_s_per_m, double friction, double normal_force_n, const Vec3& v_t,
                           const Vec3& slip_m, Vec3& spring_m) {
    spring_m += slip_m;
    const Vec3 damping = c_t_n_s_per_m * v_t;  // opposes v_t
    Vec3 force = -s_t_n_per_m * spring_m - damping;
    const double cap = friction * std::max(0.0, normal_force_n);
    const double f = force.norm();
    if (f > cap && f > 0.0) {
        // Sliding: the force at Coulomb's cap, the spring shortened to what that force holds.
        force *= cap / f;
        spring_m = s_t_n_per_m > 0.0 ? Vec3(-(force + damping) / s_t_n_per_m) : Vec3(Vec3::Zero());
    }
    return force;
}

}  // namespace peensim::contact
