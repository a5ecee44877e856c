// The outline of a standard involute spur gear in its plane (no profile shift, zero backlash):
// pitch, base, tip and root circles and the angular half-thickness of a tooth at any radius.
//
// Above the base circle a flank is the involute of the base circle. Below it (when the root
// circle is smaller than the base circle, i.e. fewer than about 42 teeth at 20 deg) the flank
// continues as a radial line down to the root circle; the trochoidal root fillet and
// undercut of a real cutter are not modelled.
#pragma once

#include <numbers>

#include "geometry/axis_frame.h"

namespace peensim {

struct SpurGearSpec {
    double module_m = 2e-3;                                       // m, pitch diameter / teeth
    int teeth = 20;                                               // -, >= 3
    double face_width_m = 10e-3;                                  // m, extent along the gear axis
    double pressure_angle_rad = 20.0 * std::numbers::pi / 180.0;  // rad, at the pitch circle
    double bore_radius_m = 5e-3;                                  // m, central hole for the axle (> 0)
    double addendum_coefficient = 1.0;                            // -, tip radius = pitch radius + this * module
    double dedendum_coefficient = 1.25;                           // -, root radius = pitch radius - this * module
    Axis axis = Axis::y;                                          // world axis of the gear
    Vec3 center_m = Vec3::Zero();                                 // m, centre of the gear (mid face width)
};

class InvoluteToothProfile {
public:
    // Throws InputError (field "gear") for a gear that cannot be built: non-positive sizes,
    // pointed teeth (tip thickness <= 0), teeth that overlap at the root, or a bore that does
    // not fit inside the root circle.
    explicit InvoluteToothProfile(const SpurGearSpec& spec);

    int teeth() const { return teeth_; }
    double pitch_radius_m() const { return pitch_radius_m_; }
    double base_radius_m() const { return base_radius_m_; }
    double tip_radius_m() const { return tip_radius_m_; }
    double root_radius_m() const { return root_radius_m_; }
    double pitch_angle_rad() const;  // rad, 2 pi / teeth: angle from one tooth centre to the next

    // Lowest radius of the involute part of the flank: max(base, root) circle (m).
    double involute_start_radius_m() const;
    // Roll angle t of the involute point at radius r >= base radius: r = r_b sqrt(1 + t^2) (rad).
    double roll_angle_at(double radius_m) const;
    // Radius of the involute point at roll angle t (m).
    double radius_at_roll(double roll_rad) const;
    // Arc length of one involute flank from involute_start_radius to the tip (m).
    double involute_length_m() const;

    // Half the angular thickness of a tooth at radius_m in [root, tip] (rad): a tooth centred
    // on angle phi covers [phi - h, phi + h] at that radius.
    double half_angle_rad(double radius_m) const;

private:
    int teeth_;
    double pitch_radius_m_;
    double base_radius_m_;
    double tip_radius_m_;
    double root_radius_m_;
    double half_angle_at_base_rad_;  // rad, pi / (2 z) + inv(pressure angle)
};

}  // namespace peensim
