// From the impacts in a patch to the deck's shots and steps. Impacts (in time order) are grouped
// into one step as long as each lands farther than `separation_dent_diameters` dent diameters
// (eq. 10, the larger of the two) from every other impact of its step and within `window_s` of the
// step's first impact; otherwise a new step starts. So two impacts whose dents can interact keep
// their order, each in its own step. Every shot flies from t = 0, placed back along its incoming
// velocity so that it comes within `gap` of the surface (along the normal) when its step begins;
// a step lasts the gap's flight plus `contact_times` Hertz contact times of its slowest impact.
// Pure computation: no I/O.
#pragma once

#include <cstdint>
#include <vector>

#include "common/vec.h"
#include "fem/fem_deck.h"

namespace peensim {

struct PatchImpact {
    std::uint64_t row = 0;                 // row of impacts.csv (1 = first after the header); 0 = synthetic
    double time_s = 0.0;                   // s, in the run
    Vec3 point_m = Vec3::Zero();           // m, patch frame, on the tangent plane (z = 0)
    double plane_offset_m = 0.0;           // m, how far above (+) or below the tangent plane the logged point was
    Vec3 velocity_m_per_s = Vec3::Zero();  // m/s, patch frame, incoming (z < 0)
    double dent_diameter_m = 0.0;          // m, eq. 10 with the normal speed
};

struct GroupingRule {
    double separation_dent_diameters = 2.0;  // -, impacts of a step are farther apart than this many dent diameters
    double window_s = 1e-3;                  // s, a step spans at most this much of the run's time
};

// Groups of indices into `impacts` (which must be in time order), in time order.
std::vector<std::vector<int>> group_impacts(const std::vector<PatchImpact>& impacts, const GroupingRule& rule);

// Hertz's contact time (s) of an elastic sphere (radius, mass) on a half-space at normal speed v:
// 2.87 (m^2 / (R E*^2 v))^(1/5), 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.
double hertz_contact_time(double radius_m, double mass_kg, double effective_modulus_pa, double normal_speed_m_per_s);

struct StepTiming {
    double gap_radii = 0.02;               // -, normal clearance of a shot at its step's start, in shot radii
    double contact_times = 3.0;            // -, a step lasts this many Hertz contact times after the gap's flight
    double increments_per_contact = 15.0;  // -, the largest increment is the contact time over this
};

// Fills deck.shots and deck.steps (the meshes and materials must be set: the shot radius is
// taken from the shot mesh's extent, materials for the contact time). Throws std::invalid_argument
// for an impact that does not approach the surface.
void plan_steps(FemDeck& deck, const std::vector<PatchImpact>& impacts, const std::vector<std::vector<int>>& groups, double shot_radius_m,
                const StepTiming& timing);

}  // namespace peensim
