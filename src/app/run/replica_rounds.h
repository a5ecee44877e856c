// A run until coverage on several cores (`peensim run --until-coverage 98% --replicas K`): the
// replicas of app/run/replica_plan.h in rounds, since the run's end is not known beforehand.
//
// How. Replica 0 is the run itself, from t = 0; its pilot measures the start-up transient and the
// impact rate. Its first slot of the log is [0, A); every later slot is W long, a whole number of
// the part's turns holding about kRoundImpacts impacts at the pilot's rate. Round r is one slot of
// every replica, laid end to end in replica order: the log is
//   replica 0 [0, A), replica 1 round 0, ..., replica K-1 round 0, replica 0 round 1, ...
// Every replica runs on from where its last slot ended (its own trajectory, its own clock); a slot
// is moved to its place in the run by a whole number of turns, so every impact keeps its angle.
// Replica k >= 1 starts its first slot after the measured warm-up, rounded up to the part's angle
// at A. The replicas wait for each other at the end of each round (the log must be written in
// time order, and the coverage counted in it); the run ends in the slot where every watched area
// reached its target, and the slots after it are dropped, so the same seed and K give the same
// bytes whatever the cores did. A round costs a wait for the slowest replica and about 1 ms of
// files; a round of kRoundImpacts keeps both small against its own simulation.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "app/run/replica_plan.h"

namespace peensim {

// The impacts a replica logs in one round, at the pilot's rate (the round is at least a turn).
inline constexpr std::uint64_t kRoundImpacts = 4 * kPilotImpacts;

struct RoundPlan {
    double pilot_s = 0.0;              // s, replica 0's time when the warm-up was measured
    double warm_up_s = 0.0;            // s, the measured start-up transient
    double turn_s = 0.0;               // s, the part's turn (0: nothing turns)
    double first_s = 0.0;              // s, A: replica 0's first slot is [0, A)
    double round_s = 0.0;              // s, W: every later slot's length
    std::vector<std::uint64_t> seeds;  // per replica (0: the scene's)
    std::vector<double> first_from_s;  // s, per replica: its own time its first slot starts (0 for replica 0)
    int replicas() const { return static_cast<int>(seeds.size()); }
    // Slot (round, replica): its own time [log_from_s, run_to_s), moved by shift_s into the run.
    ReplicaWindow slot(int round, int replica) const;
    // Its place in the run, [start, end): one formula for both, so that a slot begins exactly
    // where the one before it ended (its own times moved by shift_s agree to rounding).
    double slot_start_s(int round, int replica) const;
    double slot_end_s(int round, int replica) const;
};

// The rounds of `replicas` replicas, the warm-up measured at pilot_s among `pilot_impacts`
// impacts. nullopt when there is nothing to plan (one replica, no warm-up or no impacts).
std::optional<RoundPlan> plan_rounds(int replicas, double pilot_s, double warm_up_s, std::uint64_t pilot_impacts, double turn_s,
                                     std::uint64_t seed);

// A run until coverage only caps its duration: its pilot starts at 1 s of peening (then doubles
// as usual), so that the same seed and K give the same run whatever the cap (the cap only needs
// to leave the pilot time to settle: 2 K s and more, or less when the cap is shorter).
double first_round_pilot_s(double duration_s, int replicas);

}  // namespace peensim
