// The normal impulse of one soft contact over half a step of the soft scheme's pool
// (engine/soft/soft_pool.h), integrated along the contact's own path.
//
// Why not velocity Verlet's kick (the force at the node times half the step): that kick is a
// quadrature of the impulse, second order while the force is smooth. Hertz's force switches on and
// off as delta^3/2 (its damping as delta^1/4), so a contact that begins or ends inside a step gets
// a kick error of a sign that depends on where in the step it ends: measured in the pool at 20
// steps per contact, rebounds off by up to 3e-3 (SoftContact.ReboundRestitutionIsExactAtEverySpeed)
// and, on average, +6.9e-5 of a shot's energy per contact in an elastic bouncing load, an energy
// that grows without bound (SoftContact.ABouncingLoadKeepsItsEnergyAtEOne).
//
// The identity behind the fix: for any motion, x(t + h) = x(t) + h v(t) + h * integral over
// [0, h] of (1 - s/h) a(t + s) ds, and the same backwards. So kick-drift-kick puts every node
// exactly on the true path when each half kick is the force's impulse weighted by (1 - |s|/h)
// over its half step (a "hat" of width h on each side of the node, each side its own step).
// NodePath integrates that along the contact's path from the node: the motion the node's other
// accelerations give (held for the half step) less what the contact's own force does, that force
// (Hertz's and its damping's) taken along the straight path from the node and integrated twice in
// closed form. So the path is right where the force switches on or off (the root is found, its
// singularity mapped out of the Gauss quadrature) and where the force dominates the motion; what
// is left is the change of the other accelerations within the half step, the force's own change of
// speed acting back on it beyond the fourth derivative, and the node velocity the path starts from.
#pragma once

#include "common/vec.h"
#include "contact/soft_pair.h"

namespace peensim {

// One contact near a node: its overlap, rate and the other accelerations there, and the
// direction its normal force pushes the shot. tau (s) counts from the node.
struct ContactPath {
    double overlap_m = 0.0;             // m, delta at the node (negative: a gap)
    double rate_m_per_s = 0.0;          // m/s, d delta / dt at the node (> 0 closing)
    double outer_accel_m_per_s2 = 0.0;  // m/s2, d2 delta / dt2 from everything but this contact's normal force
    Vec3 normal = Vec3::UnitZ();        // unit, world: the force's direction on the shot at the node
    Vec3 turn_per_s = Vec3::Zero();     // 1/s, d normal / dt (two shot passing each other, a turning face; else 0)
};

// N s, world: the impulses of a contact's normal force on the shot over half a step, weighted
// two ways (see NodePath::half_step).
struct HalfStepImpulse {
    Vec3 near = Vec3::Zero();  // N s
    Vec3 far = Vec3::Zero();   // N s
};

// One contact's path from its node, built once and integrated over either half step around it:
// delta(tau) = d0 + r tau + A tau^2 / 2 - G(tau) / m* + c3 tau^3 / 6 + c4 tau^4 / 24, G the
// contact's own force (the pair's soft_normal_force, at the node's rate r) along the straight
// path x = d0 + r tau integrated twice from the node, c3 and c4 what the true motion's third and
// fourth derivatives at the node have beyond that (the force's own change of speed acting back on
// it).
class NodePath {
public:
    NodePath() = default;
    // h_max_s (s): how far from the node it is followed (the longer half step around it).
    NodePath(const contact::SoftPair& pair, const ContactPath& path, double h_max_s);

    // The impulses of the normal force on the shot over the half step from the node to tau = h
    // (s, |h| <= h_max; h < 0: the half step before the node). `near` weighs it by 1 - tau / h: the
    // node's half kick that makes the step's end exact; `far` by tau / h: the other end's share of
    // the same impulse (the next node's first estimate). Zero where the path never overlaps.
    HalfStepImpulse half_step(double h_s) const;

    // m, m/s: the overlap and its rate at tau (s).
    void at(double tau_s, double& overlap_m, double& rate_m_per_s) const;

private:
    // The most quadrature points of a half step: up to three pieces (two roots), each up to two
    // halves of 8 mapped and 8 plain points.
    static constexpr int kMaxPoints = 96;
    // at() at n <= kMaxPoints points tau[i]: the quadrature's inner loop, in plain loops over
    // arrays (which the compiler vectorizes).
    void at(const double* tau, int n, double* delta, double* rate) const;
    // The force along the straight path, k x^3/2 + c r x^1/4, integrated once (N m) and twice
    // (N m2) in x, at x (m).
    void phis(double x, double& phi1, double& phi2) const;

    double reach_s_ = 0.0;         // s, h_max (0: an empty path, for a gap that stays open on both sides)
    Vec3 normal_ = Vec3::UnitZ();  // unit
    Vec3 turn_ = Vec3::Zero();     // 1/s
    // The node's terms, the force integrated once and twice, and the force itself, for powers
    // other than Hertz's (whose terms the code above writes with square roots, the common case).
    void general_node(double h_max_s);
    void general_phis(double x, double& phi1, double& phi2) const;
    double general_force(double delta_m, double rate_m_per_s) const;  // N

    contact::SoftForceShape c_;                    // the pair's force
    bool hertz_ = true;                            // its powers are Hertz's (3/2, 1/4)
    double m_ = 1.0;                               // kg, m*
    double d0_ = 0.0, r_ = 0.0, A_ = 0.0;          // m, m/s, m/s2: the path's overlap, rate and outer acceleration at the node
    double f0_ = 0.0, f1_ = 0.0, f2_ = 0.0;        // N, N/m, N/m2: the force along the straight path and its x-derivatives at d0
    double c3_ = 0.0, c4_ = 0.0;                   // m/s3, m/s4
    double phi1_0_ = 0.0, phi2_0_ = 0.0;           // N m, N m2: the force integrated once and twice in x, at d0
    double g_scale_ = 0.0, dg_scale_ = 0.0;        // 1/(m2/s2 kg), 1/(m/s kg)
    double f0_m_ = 0.0, f1_m_ = 0.0, f2_m_ = 0.0;  // the same over m*
    bool node_overlap_exact_ = false;              // at(0) is d0_ to the bit
};

// NodePath(pair, path, |h|).half_step(h).
HalfStepImpulse half_step_impulse(const contact::SoftPair& pair, const ContactPath& path, double h_s);
// NodePath(pair, path, max(h_before, h_after)), or an empty one (no impulse either way) for a gap
// that stays open over both half steps (s).
NodePath node_path(const contact::SoftPair& pair, const ContactPath& path, double h_before_s, double h_after_s);

// m and m/s: the overlap and its rate at tau (s) along the path half_step_impulse(pair, path, h)
// integrates, |tau| <= |h| (NodePath(pair, path, |h|).at(tau, ...)).
void contact_path_at(const contact::SoftPair& pair, const ContactPath& path, double h_s, double tau_s, double& overlap_m,
                     double& rate_m_per_s);

}  // namespace peensim
