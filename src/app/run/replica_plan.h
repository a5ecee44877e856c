// A run on several cores as independent replicas of the chamber (`peensim run --replicas K`).
//
// Why it is sound. In steady state the impacts of a chamber are a stationary process: the rate,
// the places and the speeds do not depend on when one looks. K copies of the scene, each with its
// own random stream, each warmed up and then run for its share of the duration, logged one after
// another, estimate everything the analysis computes as one run of the whole duration does: the
// coverage of the union of independent dent fields is the coverage of their sum.
//
// How. Replica 0 is the run itself: the scene's seed, from t = 0 (so its start-up is the serial
// run's start-up, and its animation the run's). Its first impacts are the pilot: the warm-up (the
// start-up transient, measured by MSER-5, analysis/warm_up.h) is read from them once there are
// enough. Replica 0 then runs to T0 and each other replica k, started from rest with its own
// seed, runs its warm-up and then its window, whose impacts are logged at the times of the
// window's place in the run, [a_k, a_k + L): the windows tile [0, duration) in replica order.
// Every replica starts its own clock at 0, so its own start-up is the run's; a window shifted by
// a whole number of the part's turns keeps every impact's angle (a rotating part): the window's
// start in the replica's own time is the warm-up rounded up to the part's angle at a_k.
// Shares are sized so that all replicas end together (equal speed per simulated second).
//
// Not stationary, so refused: shot sources (the load changes), a law with an impact history
// (the surface hardens over the whole run), a run with shot snapshots (of one trajectory), parts
// turning at different speeds (no common turn to shift by). A run until coverage, whose end is
// not known beforehand, runs its replicas in rounds (app/run/replica_rounds.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "model/model.h"

namespace peensim {

struct ReplicaWindow {
    int replica = 0;                                                // 0: the run's own
    std::uint64_t seed = 0;                                         // its shot placement's seed (replica 0: the scene's)
    double log_from_s = 0.0;                                        // s, its own time its window starts (replica 0: 0)
    double run_to_s = 0.0;                                          // s, its own time it stops (the window's end)
    double shift_s = 0.0;                                           // s, added to its impacts' times: a whole number of turns of the part
    double window_start_s() const { return log_from_s + shift_s; }  // s, run time
    double window_end_s() const { return run_to_s + shift_s; }      // s, run time
};

struct ReplicaPlan {
    double pilot_s = 0.0;                // s, replica 0's time when the warm-up was measured
    double warm_up_s = 0.0;              // s, the measured start-up transient
    double turn_s = 0.0;                 // s, the part's turn (0: nothing turns)
    std::vector<ReplicaWindow> windows;  // replica order = time order; they tile [0, duration)
};

// Why `model` cannot run as replicas (a sentence), or nullopt.
std::optional<std::string> replica_refusal(const Model& model);

// The period of the turning parts (s): 0 when none turns. Only for a model replica_refusal accepts.
double turn_period_s(const Model& model);

// The seed of replica k of a scene seeded `seed` (k = 0: the scene's own).
std::uint64_t replica_seed(std::uint64_t seed, int replica);

// The windows of `replicas` replicas over [0, duration_s), the warm-up measured at pilot_s. nullopt
// when they would not save time (the duration too short for the pilot and the warm-up).
std::optional<ReplicaPlan> plan_replicas(double duration_s, int replicas, double pilot_s, double warm_up_s, double turn_s,
                                         std::uint64_t seed);

// When replica 0 next looks for the warm-up: the pilot starts at duration / (64 K) and doubles
// until MSER finds the transient's end among at least kPilotImpacts impacts, up to duration / (2 K)
// (then the run goes on as one replica).
inline constexpr std::uint64_t kPilotImpacts = 2000;
double first_pilot_s(double duration_s, int replicas);
double last_pilot_s(double duration_s, int replicas);

}  // namespace peensim
