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

// Fraction of the shot radius: an overlap (with a surface or another shot) removed by moving the
// shot out is counted in the health counters (mesh_overlap_corrections, shot_overlap_corrections)
// beyond this depth; shallower ones are roundings of a contact.
inline constexpr double kOverlapWorthCounting = 0.01;

// Fraction of the shot radius: a shot found this deep in a surface (its centre half a radius in)
// is a deep penetration (health counter deep_penetrations, serious): something let it through.
inline constexpr double kDeepPenetration = 0.5;

}  // namespace peensim::contact
