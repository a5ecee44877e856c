#include "contact/impulse_laws.h"

#include <algorithm>

#include "contact/restitution.h"

namespace peensim::contact {

ShotShotResponse ImpulseShotShotLaw::respond(const ShotShotInput& in, const PairCoefficients& k) const {
    ShotShotResponse out{in.v_i, in.v_j, 0.0, false};
    const double dV = (in.v_j - in.v_i).dot(in.normal);  // < 0 while approaching
    if (!(dV < 0.0)) return out;
    const double C = normal_restitution(-dV, k.C0, k.V0_m_per_s);
    const Vec3 impulse_per_mass = 0.5 * (1.0 + C) * dV * in.normal;
    out.v_i = in.v_i + impulse_per_mass;
    out.v_j = in.v_j - impulse_per_mass;
    out.vn_in = -dV;
    out.approaching = true;
    return out;
}

namespace {

struct RelativeParts {
    double vn;    // m/s, normal relative velocity (< 0 approaching)
    Vec3 vt;      // m/s, tangential relative velocity
};

RelativeParts split(const SurfaceContactInput& in) {
    const Vec3 dV = in.v_shot - in.v_surface;
    const double vn = dV.dot(in.normal);
    return {vn, dV - vn * in.normal};
}

}  // namespace

SurfaceContactResponse ImpulseSurfaceLaw::impact(const SurfaceContactInput& in, const PairCoefficients& k) const {
    const RelativeParts rel = split(in);
    SurfaceContactResponse out;
    out.v_shot = in.v_shot;
    out.vn_in = std::max(0.0, -rel.vn);
    out.vt_in = rel.vt.norm();
    if (!(rel.vn < 0.0)) return out;
    const double C = normal_restitution(-rel.vn, k.C0, k.V0_m_per_s);
    out.v_shot = in.v_surface + k.mu * rel.vt - C * rel.vn * in.normal;
    out.vn_out = -C * rel.vn;
    out.approaching = true;
    return out;
}

SurfaceContactResponse ImpulseSurfaceLaw::sustain(const SurfaceContactInput& in, const PairCoefficients& k) const {
    const RelativeParts rel = split(in);
    SurfaceContactResponse out;
    out.vn_in = std::max(0.0, -rel.vn);
    out.vt_in = rel.vt.norm();
    out.approaching = rel.vn < 0.0;
    // Coulomb: the tangential speed drops by at most f * (pressing acceleration) * dt, never reversing.
    const double slowdown = k.f * std::max(0.0, in.pressing_accel) * in.dt;
    const Vec3 vt = out.vt_in > slowdown ? Vec3(rel.vt * (1.0 - slowdown / out.vt_in)) : Vec3(Vec3::Zero());
    const double vn = std::max(0.0, rel.vn);  // an approach is stopped; a separation is kept
    out.v_shot = in.v_surface + vt + vn * in.normal;
    out.vn_out = vn;
    return out;
}

}  // namespace peensim::contact
