// Rebound scatter (reference section 5): above a relative Reynolds number Re* ~ 1600 and an impact
// speed of ~40 m/s the single-shot study saw the rebound leave in a visibly random direction (an
// asymmetric dent, vortices). Modelled as a random tangential deflection of the rebound: its
// direction relative to the surface turns by an angle uniform in [0, spread] towards a uniformly
// random direction in the surface's plane, its speed kept (so the normal rebound speed only falls:
// no energy is added). Off unless the scene asks for it (`air.rebound_scatter`).
//
// A wrapper around any surface law: the law decides the rebound, the scatter turns it. The random
// numbers are a function of the scene's seed and the contact (shot, triangle, time) alone: a pure
// law, the same rebound whenever the same contact is asked about (a resumed run, the other scheme
// at the same contact).
#pragma once

#include <cstdint>
#include <memory>

#include "contact/contact_law.h"

namespace peensim::contact {

struct ReboundScatter {
    double spread_rad = 0.0;          // rad, largest deflection
    double min_reynolds = 1600.0;     // -, Re* = rho_air |v| D / mu_air at the impact (still air)
    double min_speed_m_per_s = 40.0;  // m/s, impact speed relative to the surface
    double air_density_kg_per_m3 = 1.205;
    double air_viscosity_pa_s = 1.822e-5;
    std::uint64_t seed = 0;
};

// Whether an impact at relative speed `speed` (m/s) of a shot of diameter `diameter` (m) scatters.
bool scatters(const ReboundScatter& s, double speed_m_per_s, double diameter_m);

// The rebound velocity relative to the surface `u` (m/s; u . n > 0) turned by `angle_rad` towards
// the unit direction `t` of the surface's plane, at the same speed.
Vec3 deflected(const Vec3& u, const Vec3& n, const Vec3& t, double angle_rad);

std::shared_ptr<const SurfaceLaw> with_rebound_scatter(std::shared_ptr<const SurfaceLaw> law, const ReboundScatter& scatter);

}  // namespace peensim::contact
