#include "contact/impulse_laws.h"

#include <algorithm>
#include <array>

#include "contact/restitution.h"

namespace peensim::contact {

namespace {

// Reference tables 1 and 2; the defaults are the reference's shot-sonotrode-like values.
constexpr std::array kImpulseParameters{
    LawParameter{"C0", Dimension::dimensionless, "0.9", open_closed(0, 1), false, "Normal restitution in the elastic regime (eq. 2)."},
    LawParameter{"V0", Dimension::speed, "0.5", above(0), false, "Impact speed where the plastic regime starts (eq. 2)."},
    LawParameter{"mu", Dimension::dimensionless, "0.71", closed(0, 1), false, "Tangential restitution (eq. 4, 5); not for `shot-shot`."},
    LawParameter{"f", Dimension::dimensionless, "0.1", at_least(0), false, "Coulomb friction in sustained contact; not for `shot-shot`."},
};

struct RelativeParts {
    double vn;  // m/s, normal relative velocity (< 0 approaching)
    Vec3 vt;    // m/s, tangential relative velocity
};

RelativeParts split(const SurfaceContactInput& in) {
    const Vec3 dV = in.v_shot - in.v_surface;
    const double vn = dV.dot(in.normal);
    return {vn, dV - vn * in.normal};
}

}  // namespace

std::span<const LawParameter> impulse_parameters() { return kImpulseParameters; }

PairCoefficients impulse_coefficients(const ParameterValues& values) {
    // Shot-shot pairs give only C0 and V0; mu and f keep their defaults there (unused).
    PairCoefficients k;
    k.C0 = values.scalar("C0");
    k.V0_m_per_s = values.scalar("V0");
    if (values.has("mu")) k.mu = values.scalar("mu");
    if (values.has("f")) k.f = values.scalar("f");
    return k;
}

ShotShotResponse impulse_shot_shot(const ShotShotInput& in, const PairCoefficients& k) {
    ShotShotResponse out{in.v_i, in.v_j, 0.0, false};
    const double dV = (in.v_j - in.v_i).dot(in.normal);  // < 0 while approaching
    if (!(dV < 0.0)) return out;
    double C = 0.0;
    switch (in.mode) {
        case ShotShotMode::law: C = normal_restitution(-dV, k.C0, k.V0_m_per_s); break;
        case ShotShotMode::sustained: C = 0.0; break;
        case ShotShotMode::collapse_guard: C = normal_restitution(-dV, 1.0, k.V0_m_per_s); break;
    }
    // The impulse (1 + C) dV m_i m_j / (m_i + m_j) changes each velocity in inverse proportion to
    // its mass (impulse_shares).
    const ImpulseShares share = impulse_shares(in);
    const Vec3 exchange = (1.0 + C) * dV * in.normal;
    out.v_i = in.v_i + share.i * exchange;
    if (!in.j_held) out.v_j = in.v_j - share.j * exchange;
    out.vn_in = -dV;
    out.approaching = true;
    return out;
}

SurfaceContactResponse impulse_surface_rebound(const SurfaceContactInput& in, double C, double mu) {
    const RelativeParts rel = split(in);
    SurfaceContactResponse out;
    out.v_shot = in.v_shot;
    out.vn_in = std::max(0.0, -rel.vn);
    out.vt_in = rel.vt.norm();
    if (!(rel.vn < 0.0)) return out;
    out.v_shot = in.v_surface + mu * rel.vt - C * rel.vn * in.normal;
    out.vn_out = -C * rel.vn;
    out.approaching = true;
    return out;
}

SurfaceContactResponse impulse_surface_impact(const SurfaceContactInput& in, const PairCoefficients& k) {
    const double vn = (in.v_shot - in.v_surface).dot(in.normal);
    return impulse_surface_rebound(in, normal_restitution(std::max(0.0, -vn), k.C0, k.V0_m_per_s), k.mu);
}

SurfaceContactResponse impulse_surface_sustain(const SurfaceContactInput& in, double f) {
    const RelativeParts rel = split(in);
    SurfaceContactResponse out;
    out.vn_in = std::max(0.0, -rel.vn);
    out.vt_in = rel.vt.norm();
    out.approaching = rel.vn < 0.0;
    // Coulomb: the tangential speed drops by at most f * (pressing acceleration) * dt, never reversing.
    const double slowdown = f * std::max(0.0, in.pressing_accel) * in.dt;
    const Vec3 vt = out.vt_in > slowdown ? Vec3(rel.vt * (1.0 - slowdown / out.vt_in)) : Vec3(Vec3::Zero());
    const double vn = std::max(0.0, rel.vn);  // an approach is stopped; a separation is kept
    out.v_shot = in.v_surface + vt + vn * in.normal;
    out.vn_out = vn;
    return out;
}

}  // namespace peensim::contact
