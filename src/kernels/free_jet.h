// The air a nozzle blows: a round turbulent free jet, self-similar (Pope, Turbulent Flows, 2000,
// ch. 5.1; Hussein, Capp & George 1994), from an exit of diameter D_n at air speed U_0 along the
// unit axis d. At distance s downstream of the exit and r off the axis:
//
//   centreline speed   U_c(s) = U_0 min(1, B D_n / s)           B = 5.8 (decay constant)
//   half-width         r_h(s) = max(D_n / 2, S s)               S = 0.094 (spreading rate)
//   profile            u(r, s) = U_c(s) exp(-ln 2 (r / r_h)^2) d
//
// so the potential core (U_0 on the axis) reaches B D_n = 5.8 D_n, where the half-width S B D_n =
// 0.55 D_n has just outgrown the exit's radius; upstream of the exit (s <= 0) the air is still. The
// jet is free: the part does not turn it (a real jet spreads along the wall it meets, as a wall
// jet, within about a nozzle diameter of it), and several jets add.
#pragma once

#include <vector>

#include "common/vec.h"

namespace peensim {

struct FreeJet {
    static constexpr double kDecayConstant = 5.8;   // B
    static constexpr double kSpreadingRate = 0.094;  // S
    Vec3 exit_m = Vec3::Zero();  // m, the exit's centre, world
    Vec3 axis = -Vec3::UnitZ();  // unit, world
    double exit_diameter_m = 0.0;   // m, D_n
    double exit_speed_m_per_s = 0.0;  // m/s, U_0 (the air's, not the shot's)

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
