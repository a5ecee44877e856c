#include "geometry/spur_gear_profile.h"

#include <algorithm>
#include <cmath>

#include "common/input_error.h"

namespace peensim {

namespace {

[[noreturn]] void reject(const std::string& problem) { throw InputError({}, "gear", problem); }

double involute_function(double angle_rad) { return std::tan(angle_rad) - angle_rad; }

}  // namespace

InvoluteToothProfile::InvoluteToothProfile(const SpurGearSpec& spec) : teeth_(spec.teeth) {
    if (!(spec.module_m > 0.0)) reject("module must be positive");
    if (spec.teeth < 3) reject("a gear needs at least 3 teeth");
    if (!(spec.face_width_m > 0.0)) reject("face width must be positive");
    if (!(spec.pressure_angle_rad > 0.0 && spec.pressure_angle_rad < std::numbers::pi / 4.0)) {
        reject("pressure angle must lie between 0 and 45 degrees");
    }
    if (!(spec.addendum_coefficient > 0.0 && spec.dedendum_coefficient > 0.0)) {
        reject("addendum and dedendum coefficients must be positive");
    }
    pitch_radius_m_ = 0.5 * spec.module_m * spec.teeth;
    base_radius_m_ = pitch_radius_m_ * std::cos(spec.pressure_angle_rad);
    tip_radius_m_ = pitch_radius_m_ + spec.addendum_coefficient * spec.module_m;
    root_radius_m_ = pitch_radius_m_ - spec.dedendum_coefficient * spec.module_m;
    // Tooth thickness on the pitch circle is half the circular pitch (pi m / 2): half-angle
    // pi / (2 z) there, plus inv(alpha) back down to the base circle.
    half_angle_at_base_rad_ = std::numbers::pi / (2.0 * spec.teeth) + involute_function(spec.pressure_angle_rad);

    if (!(spec.bore_radius_m > 0.0)) reject("bore radius must be positive");
    if (!(spec.bore_radius_m < root_radius_m_)) reject("bore must be smaller than the root circle");
    if (!(tip_radius_m_ > base_radius_m_)) reject("tip circle must lie outside the base circle");
    if (!(half_angle_rad(tip_radius_m_) > 0.0)) reject("teeth are pointed: fewer teeth or a smaller addendum needed");
    if (!(half_angle_rad(root_radius_m_) < 0.5 * pitch_angle_rad())) reject("teeth overlap at the root circle");
}

double InvoluteToothProfile::pitch_angle_rad() const { return 2.0 * std::numbers::pi / teeth_; }

double InvoluteToothProfile::involute_start_radius_m() const { return std::max(base_radius_m_, root_radius_m_); }

double InvoluteToothProfile::roll_angle_at(double radius_m) const {
    const double ratio = radius_m / base_radius_m_;
    return std::sqrt(std::max(0.0, ratio * ratio - 1.0));
}

double InvoluteToothProfile::radius_at_roll(double roll_rad) const { return base_radius_m_ * std::sqrt(1.0 + roll_rad * roll_rad); }

double InvoluteToothProfile::involute_length_m() const {
    // Arc length of the involute of a circle: s(t) = r_b t^2 / 2.
    const double t_start = roll_angle_at(involute_start_radius_m());
    const double t_tip = roll_angle_at(tip_radius_m_);
    return 0.5 * base_radius_m_ * (t_tip * t_tip - t_start * t_start);
}

double InvoluteToothProfile::half_angle_rad(double radius_m) const {
    if (radius_m <= base_radius_m_) return half_angle_at_base_rad_;  // radial flank
    // inv(alpha_r) with cos(alpha_r) = r_b / r, i.e. tan(alpha_r) = t: inv = t - atan(t).
    const double t = roll_angle_at(radius_m);
    return half_angle_at_base_rad_ - (t - std::atan(t));
}

}  // namespace peensim
