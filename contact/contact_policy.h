// The contact policy both stepping schemes follow: where an impact ends and sustained contact
// begins, and which overlaps the health counters report. One place, so that the schemes draw the
// same lines (a scheme may resolve a contact differently, never classify it differently).
#pragma once

namespace peensim::contact {

// The line between an impact and sustained contact: the normal approach speed (m/s) against the
// scene's `accuracy.impact_speed` (m/s, Model::impact_speed_m_per_s), the same for every scheme
// and every pair. An approach at least that fast is an impact, a slower one sustained contact.
// Without such a line a resting shot would bounce forever in ever smaller hops (a Zeno sequence)
// and jitter on the surface; a fixed speed, unlike one tied to a scheme's step, puts it at the
// same place whatever the scheme and the step.
inline bool is_impact(double approach_speed, double impact_speed) { return approach_speed >= impact_speed; }

// m/s: a rebound from a surface that accelerates into the shot faster than gravity (the vibrating
// plate) slower than this is a ride: the shot stays on the plate until the plate pulls away. Every
// faster rebound, impact or slow touch, is followed (the chatter sequence, each impact counted), by
// both schemes. Below this the gap would open by less than ~1e-12 m (u^2 / 2a at a plate
// acceleration a ~ 4e5 m/s2), the rounding of a contact time, so nothing slower can be resolved.
// (Time stepping once made every slow touch on a pressing plate a ride: near the plate's release
// that launched shot at the plate's speed which really left on their own rebound; the 1 mm / 80 um
// tube's ceiling impacts came out 0.1 % fast over 3000 s, 4.7 standard errors.)
inline constexpr double kRideSpeed = 1e-3;

// closing_acceleration: the surface's acceleration into the shot minus gravity's, along the
// normal (m/s2); rebound_speed: the shot's normal speed away from the surface after the contact
// law (m/s); floor_speed: a scheme's own resolution limit (m/s), used when larger than kRideSpeed.
inline bool rebound_rides(double closing_acceleration, double rebound_speed, double floor_speed = 0.0) {
    return closing_acceleration > 0.0 && rebound_speed < (floor_speed > kRideSpeed ? floor_speed : kRideSpeed);
}

// How the contact policy has the law resolve a shot-shot contact (contact_policy.h).
enum class ShotShotMode {
    law,        // the law's own restitution
    sustained,  // slower than the scheme can follow: the approach stops, nothing bounces
    // The TC rule (Luding and McNamara's collapse guard): a collision right after another loses no
    // energy the law can spare. The impulse law sets its elastic-regime restitution C0 to 1 (no
    // loss below V0, the plastic regime's loss above: a true C = 1 there changed the rod's impact
    // count by 5 % in 0.5 s, a physics change this refactor does not make).
    collapse_guard,
};

// How a scheme has the shot-shot law resolve a contact approaching at approach_speed (m/s):
// slower than the scheme follows rebounds (resting_speed, m/s: its resolution) the approach stops;
// a collision right after another of either shot (within the TC window, the scheme's) takes the
// collapse guard; otherwise the law's restitution.
inline ShotShotMode shot_shot_mode(double approach_speed, double resting_speed, bool right_after_another) {
    if (!(approach_speed > resting_speed)) return ShotShotMode::sustained;
    return right_after_another ? ShotShotMode::collapse_guard : ShotShotMode::law;
}

// Fraction of the shot radius: an overlap (with a surface or another shot) removed by moving the
// shot out is counted in the health counters (mesh_overlap_corrections, shot_overlap_corrections)
// beyond this depth; shallower ones are roundings of a contact.
inline constexpr double kOverlapWorthCounting = 0.01;

// Fraction of the shot radius: a shot found this deep in a surface (its centre half a radius in)
// is a deep penetration (health counter deep_penetrations, serious): something let it through.
inline constexpr double kDeepPenetration = 0.5;

}  // namespace peensim::contact
