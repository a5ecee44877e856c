// The air a nozzle blows: a round turbulent free jet (Pope, Turbulent Flows, 2000, ch. 5.1; Hussein,
// Capp & George 1994), from an exit of diameter D_n at air speed U_0 along the unit axis d, at
// distance s downstream of the exit and r off the axis:
//
//   potential core, s < s_c = B D_n      core radius r_c(s) = (D_n / 2)(1 - s / s_c) at U_0, and a
//   (the zone of flow establishment)    mixing layer of half-width b(s) = S s around it:
//                                        u = U_0 for r <= r_c, U_0 exp(-ln 2 ((r - r_c) / b)^2) beyond
//   self-similar, s >= s_c               U_c(s) = U_0 s_c / s on the axis, half-width r_h(s) = S s:
//                                        u = U_c exp(-ln 2 (r / r_h)^2)
//   B = 5.8 (the centreline decay constant), S = 0.094 (the spreading rate)
//
// At the exit the profile is the nozzle's top hat; at s_c the core has closed and the two forms
// are one (r_c = 0, b = r_h). The core carries U_0 out to the exit's radius near the exit (a
// Gaussian from the exit gave shot by the nozzle wall 0.76 U_0 at r = 1.9 mm of a 6 mm nozzle).
// Upstream of the exit (s <= 0) the air is still. The jet is free: the part does not turn it (a
// real jet spreads along the wall it meets, as a wall jet, within about a nozzle diameter of it),
// and several jets add.
#pragma once

#include <vector>

#include "common/vec.h"

namespace peensim {

struct FreeJet {
    static constexpr double kDecayConstant = 5.8;    // B: the core's length in exit diameters
    static constexpr double kSpreadingRate = 0.094;  // S: half-width growth per length
    Vec3 exit_m = Vec3::Zero();                      // m, the exit's centre, world
    Vec3 axis = -Vec3::UnitZ();                      // unit, world
    double exit_diameter_m = 0.0;                    // m, D_n
    double exit_speed_m_per_s = 0.0;                 // m/s, U_0 (the air's, not the shot's)

    Vec3 velocity_at(const Vec3& p) const;
};

// The air's velocity: still, plus every jet's.
class AirVelocityField {
public:
    explicit AirVelocityField(std::vector<FreeJet> jets);
    Vec3 at(const Vec3& p) const;
    // m/s, the fastest the air moves anywhere (the sum of the jets' exit speeds).
    double max_speed() const { return max_speed_; }
    bool empty() const { return jets_.empty(); }

private:
    std::vector<FreeJet> jets_;
    double max_speed_ = 0.0;
};

}  // namespace peensim
