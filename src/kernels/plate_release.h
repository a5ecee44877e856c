// Where a shot riding the vibrating plate leaves it, shared by both stepping schemes.
//
// A shot at rest on the plate is pressed while the plate's acceleration along the normal n beats
// gravity's; it leaves (is released) the instant the plate's acceleration falls to g.n, with the
// plate's velocity there. From then on it is in free flight: the plate decelerates faster than
// gravity, so the gap opens. The schemes start that flight a short delay after the release (a
// flight that starts exactly at it starts with zero gap, zero relative speed and zero relative
// acceleration: rounding could read it as a new touch), but with the state of the free flight from
// the release, not the plate's state at the later moment: the plate's jerk (A w^3 ~ 1.6e11 m/s3 at
// 80 um and 20 kHz) would take jerk d^2 / 2 (2e-6 m/s after 5 ns) off every launch.
#pragma once

#include "common/vec.h"

namespace peensim {

// Periods of free flight from the release before the schemes look for the next contact.
constexpr double kReleaseDelayPeriods = 1e-4;

// Seconds from a plate phase (rad) to the next release, where sin(phase) rises through
// eps = -g.n / (A w^2 a.n) (the plate's acceleration -A w^2 a.n sin(phase) along n then equals
// g.n); w in rad/s. Infinite if eps >= 1 (the plate never pulls away faster than gravity).
double seconds_to_release(double phase_rad, double eps, double angular_frequency_rad_per_s);

struct FlightState {
    Vec3 position_m = Vec3::Zero();
    Vec3 velocity_m_per_s = Vec3::Zero();
};

// The free flight `delay_s` after leaving `at_release` (position and velocity at the release)
// under gravity `g`.
FlightState after_release(const FlightState& at_release, const Vec3& g_m_per_s2, double delay_s);

}  // namespace peensim
