// What the event-driven scheme keeps per shot: its motion (a flight, a ride on the sonotrode's
// face, sustained contact in substeps, or asleep), its pending wall and pair events, its flight
// box, and the bookkeeping of the degenerate regimes (TC rule, grazes, sleep). Flat records in one
// array, read by the scheme, its wall predictor's caller and its pair predictor.
#pragma once

#include <cstdint>

#include "common/vec.h"
#include "engine/event/wall_event.h"
#include "kernels/trajectory.h"

namespace peensim {

// pooled: a member of the pool of the scheme on top of the event core (hand_off_pool.h: the soft
// scheme's soft contacts), which moves it; `path` is the pool's latest state of it.
enum class EventMotion : unsigned char { flying, riding, sustained, sleeping, pooled };

struct EventShot {
    Trajectory path;        // world; for a sleeping or riding shot: g = 0 (see ride_*)
    double radius_m = 0.0;  // m, the shot's radius (its size's: the size of a slot's shot never changes while it is active)
    EventMotion motion = EventMotion::flying;
    std::uint32_t version = 0;  // bumped whenever `path` changes
    WallEvent wall;
    double pair_time = 0.0;  // s, +inf: none
    int partner = -1;
    std::uint32_t partner_version = 0;
    double box_until = 0.0;                             // s, the neighbour box holds the shot up to this time
    Vec3 box_lo = Vec3::Zero(), box_hi = Vec3::Zero();  // m, that box
    double last_pair_time = -1.0;                       // s, latest shot-shot collision (TC rule)
    int last_partner = -1;
    double no_pairs_at = -1.0;   // s, an instant at which this shot takes no more pair events
    double graze_at = -1.0;      // s, the instant of its latest graze (no wall contact then)
    int quick_grazes = 0;        // grazes in a row, each within the TC window of the one before
    bool in_flight = false;      // SimulationState's in_flight (a slow contact ending it is counted)
    double substep_s = 0.0;      // s, length of the current sustained-contact substep
    int quiet_substeps = 0;      // consecutive still substeps (sleep)
    double window_travel = 0.0;  // m, travel the next search window of this flight covers
    int resumed_searches = 0;    // its searches in a row that ran out of iterations (search fallback; a search that does not resets it)
    // Riding sonotrode ride_component since ride_start (s): centre at ride_point + a (s(t) -
    // s(ride_start)) + ride_tangential (t - ride_start).
    int ride_component = -1;
    double ride_start = 0.0;
    Vec3 ride_point = Vec3::Zero();
    Vec3 ride_tangential = Vec3::Zero();
    Vec3 ride_normal = Vec3::UnitZ();
};

}  // namespace peensim
