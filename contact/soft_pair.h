// A soft-sphere contact's constants, as its law fixed them when the contact began, and the forces
// that follow from them: what the soft scheme (src/engine/soft/) integrates, whatever the law.
// Every soft law of this project (and the two that LIGGGHTS and EDEM offer) has a normal force
// that is a power of the overlap plus a damping proportional to a power of it times the overlap's
// rate, and a tangential spring capped by Coulomb; a pair says which family it belongs to and the
// functions below give its forces. A new soft law adds its family here and in soft_pair.cpp,
// its law file and its registration (law_registry.cpp): nothing in the engine changes.
#pragma once

#include <array>
#include <cstddef>

#include "common/vec.h"

namespace peensim::contact {

enum class SoftFamily : unsigned char {
    hertz_mindlin,          // Hertz's normal force, Mindlin's tangential spring (hertz_mindlin.h)
    linear_spring_dashpot,  // constant stiffnesses and dampers (linear_spring_dashpot_law.h)
};

struct SoftPair {
    SoftFamily family = SoftFamily::hertz_mindlin;
    double R_star_m = 0.0;   // m, 1/R* = 1/R_i + 1/R_j (a wall: R_j infinite)
    double m_star_kg = 0.0;  // kg, 1/m* = 1/m_i + 1/m_j (a wall: m_j infinite)
    double friction = 0.0;   // -, Coulomb's coefficient
    double beta = 0.0;       // -, ln e / sqrt(ln^2 e + pi^2): 0 for e = 1, negative below
    // hertz_mindlin
    double E_star_pa = 0.0;  // Pa, 1/E* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j
    double G_star_pa = 0.0;  // Pa, 1/G* = 2 (2 - nu_i)(1 + nu_i)/E_i + 2 (2 - nu_j)(1 + nu_j)/E_j
    // linear_spring_dashpot
    double normal_stiffness_n_per_m = 0.0;      // N/m, k_n
    double tangential_stiffness_n_per_m = 0.0;  // N/m, k_t
};

// The normal force's shape, F = elastic delta^elastic_power + damping delta^damping_power
// d delta/dt, for an integrator that needs the force's form rather than its value (the soft
// pool's exact normal kicks, src/engine/soft/contact_impulse.h).
struct SoftForceShape {
    double elastic = 0.0;        // N/m^elastic_power
    double elastic_power = 1.0;  // -
    double damping = 0.0;        // N s/m^(1 + damping_power), >= 0
    double damping_power = 0.0;  // -
};
SoftForceShape soft_force_shape(const SoftPair& p);

// N, the normal force pushing the two apart at overlap delta (m, >= 0) closing at delta_rate (m/s,
// > 0 while approaching). Not clamped: a damped contact pulls slightly at the very end of its
// restitution (the caller decides).
double soft_normal_force(const SoftPair& p, double delta_m, double delta_rate_m_per_s);

// What a soft contact remembers while it lasts, as its law's per-contact state (the same mechanism
// as SurfaceLaw::state_per_contact: the law declares it, the engine keeps it with the contact and
// in the checkpoint, zeros when the contact begins, and never reads it). Both families keep their
// tangential spring (m, world) there.
inline constexpr std::size_t kSoftStatePerContact = 3;
using SoftContactState = std::array<double, kSoftStatePerContact>;

// The state of a contact whose normal is now n (unit, world): the spring carried onto the new
// tangent plane, its length kept, so a contact that rolls or turns keeps its elastic slip.
// (LIGGGHTS 3.8's `tangential history` projects it without restoring the length: shorter by
// 1 - cos of the turn per step, second order in it.)
void soft_turn_state(const SoftPair& p, SoftContactState& state, const Vec3& n);

// N, the tangential force on body a (opposing the slip), the state's spring extended by slip_m
// (this step's elastic slip), the damping acting on v_t (m/s, of a against b, in the contact
// plane), at overlap delta (m) under normal force f_n (N); capped at friction f_n (the spring then
// shortened to match: a slider).
Vec3 soft_tangential_force(const SoftPair& p, double delta_m, double normal_force_n, const Vec3& v_t, const Vec3& slip_m,
                           SoftContactState& state);

// J, the elastic energy stored at overlap delta (m).
double soft_elastic_energy(const SoftPair& p, double delta_m);

// s, how long an impact at approach speed v (m/s) lasts (the elastic one for Hertz; the damped
// one, exactly, for the linear law): the soft scheme's steps are a share of it.
double soft_contact_duration(const SoftPair& p, double v_m_per_s);

// The tangential force of a spring of stiffness s_t (N/m) and a damper of coefficient c_t (N s/m,
// >= 0), capped at friction f_n: both families' (their stiffnesses differ). spring_m is extended
// by slip_m first.
Vec3 capped_spring_dashpot(double s_t_n_per_m, double c_t_n_s_per_m, double friction, double normal_force_n, const Vec3& v_t,
                           const Vec3& slip_m, Vec3& spring_m);

}  // namespace peensim::contact
