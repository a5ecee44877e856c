#include "app/run/replica_rounds.h"

#include <algorithm>
#include <cmath>

namespace peensim {

ReplicaWindow RoundPlan::slot(int round, int replica) const {
    const double K = static_cast<double>(replicas());
    const double r = static_cast<double>(round);
    ReplicaWindow w;
    w.replica = replica;
    w.seed = seeds.at(static_cast<std::size_t>(replica));
    if (replica == 0) {
        // Its own clock runs on; by round r the other replicas' r slots of W each came before.
        w.log_from_s = round == 0 ? 0.0 : first_s + (r - 1.0) * round_s;
        w.run_to_s = first_s + r * round_s;
        w.shift_s = r * (K - 1.0) * round_s;
        return w;
    }
    const double from = first_from_s.at(static_cast<std::size_t>(replica));
    w.log_from_s = from + r * round_s;
    w.run_to_s = from + (r + 1.0) * round_s;
    // The slot's place: A + (r K + k - 1) W in the run (first_s - from is whole turns).
    w.shift_s = (first_s - from) + (r * K + static_cast<double>(replica) - 1.0 - r) * round_s;
    return w;
}

double RoundPlan::slot_start_s(int round, int replica) const {
    if (round == 0 && replica == 0) return 0.0;
    return first_s + static_cast<double>(round * replicas() + replica - 1) * round_s;
}

double RoundPlan::slot_end_s(int round, int replica) const {
    return replica + 1 < replicas() ? slot_start_s(round, replica + 1) : slot_start_s(round + 1, 0);
}

std::optional<RoundPlan> plan_rounds(int replicas, double pilot_s, double warm_up_s, std::uint64_t pilot_impacts, double turn_s,
                                     std::uint64_t seed) {
    if (replicas < 2 || !(pilot_s > 0.0) || !(warm_up_s > 0.0) || pilot_impacts == 0) return std::nullopt;
    RoundPlan p;
    p.pilot_s = pilot_s;
    p.warm_up_s = warm_up_s;
    p.turn_s = turn_s;
    const double rate_per_s = static_cast<double>(pilot_impacts) / pilot_s;
    const double wanted_s = static_cast<double>(kRoundImpacts) / rate_per_s;
    p.round_s = turn_s > 0.0 ? std::max(1.0, std::ceil(wanted_s / turn_s)) * turn_s : wanted_s;
    // Replica 0 runs on from the pilot while the others warm up and run their first slot.
    p.first_s = pilot_s + warm_up_s + p.round_s;
    for (int k = 0; k < replicas; ++k) {
        p.seeds.push_back(replica_seed(seed, k));
        // At least the warm-up, a whole number of turns before A (the part's angle the same in both).
        p.first_from_s.push_back(k == 0 ? 0.0 : turn_s > 0.0 ? warm_up_s + std::fmod(p.first_s - warm_up_s, turn_s) : warm_up_s);
    }
    return p;
}

double first_round_pilot_s(double duration_s, int replicas) { return std::min(1.0, last_pilot_s(duration_s, replicas)); }

}  // namespace peensim
