#include "app/run/replica_plan.h"

#include <cmath>
#include <vector>

namespace peensim {

std::optional<std::string> replica_refusal(const Model& model) {
    if (!model.sources.empty())
        return "the scene has shot sources: its load changes over the run, so the run is not the same at every time";
    if (model.description.output.shot_positions_s)
        return "the scene writes shot snapshots (output.shot_positions): those are of one trajectory";
    double omega = 0.0;
    for (const Component& c : model.components) {
        if (c.law && c.law->state_per_triangle() > 0)
            return "component '" + c.name + "' has a law with an impact history (" + std::string(c.law->name()) +
                   "): its surface changes over the whole run";
        if (c.kinematics.kind != Kinematics::Kind::rotating || c.kinematics.omega_rad_per_s == 0.0) continue;
        const double w = std::abs(c.kinematics.omega_rad_per_s);
        if (omega != 0.0 && w != omega) return "parts turn at different speeds: a window cannot be shifted by a whole turn of each";
        omega = w;
    }
    return std::nullopt;
}

double turn_period_s(const Model& model) {
    for (const Component& c : model.components)
        if (c.kinematics.kind == Kinematics::Kind::rotating && c.kinematics.omega_rad_per_s != 0.0)
            return 2.0 * M_PI / std::abs(c.kinematics.omega_rad_per_s);
    return 0.0;
}

std::uint64_t replica_seed(std::uint64_t seed, int replica) {
    // Random's constructor mixes the seed (splitmix64), so consecutive seeds give unrelated streams.
    return seed + static_cast<std::uint64_t>(replica) * 0x9E3779B97F4A7C15ull;
}

std::optional<ReplicaPlan> plan_replicas(double duration_s, int replicas, double pilot_s, double warm_up_s, double turn_s,
                                         std::uint64_t seed) {
    if (replicas < 2 || !(duration_s > 0.0) || !(pilot_s >= 0.0) || !(warm_up_s > 0.0)) return std::nullopt;
    // From the pilot on, replica 0 runs T0 - P and every other replica k its warm-up W_k plus its share
    // L_k, all ending together: T0 - P = W_k + L_k and T0 + sum L_k = T, so
    // T0 = (T + (K - 1) P + sum W_k) / K. W_k is the warm-up rounded up to the part's angle at the
    // window's start, which depends on the shares: a few passes settle it (what is left is within
    // a turn's imbalance).
    const auto n = static_cast<std::size_t>(replicas);
    std::vector<double> warm(n, warm_up_s);  // W_k, k >= 1 (warm[0] unused)
    std::vector<double> start(n, 0.0);       // a_k, run time
    double t0 = 0.0;
    for (int pass = 0; pass < 8; ++pass) {
        double sum_warm = 0.0;
        for (std::size_t k = 1; k < n; ++k) sum_warm += warm[k];
        t0 = (duration_s + static_cast<double>(replicas - 1) * pilot_s + sum_warm) / static_cast<double>(replicas);
        double a = t0;
        for (std::size_t k = 1; k < n; ++k) {
            start[k] = a;
            // At least the warm-up, and a whole number of turns before a_k (the part's angle the same in both).
            warm[k] = turn_s > 0.0 ? warm_up_s + std::fmod(a - warm_up_s, turn_s) : warm_up_s;
            a += t0 - pilot_s - warm[k];
        }
    }
    if (!(t0 > pilot_s) || !(t0 < duration_s)) return std::nullopt;
    for (std::size_t k = 1; k < n; ++k)
        if (!(t0 - pilot_s - warm[k] > 0.0)) return std::nullopt;
    ReplicaPlan plan;
    plan.pilot_s = pilot_s;
    plan.warm_up_s = warm_up_s;
    plan.turn_s = turn_s;
    ReplicaWindow own;
    own.seed = seed;
    own.run_to_s = t0;
    plan.windows.push_back(own);
    for (std::size_t k = 1; k < n; ++k) {
        ReplicaWindow w;
        w.replica = static_cast<int>(k);
        w.seed = replica_seed(seed, w.replica);
        w.log_from_s = turn_s > 0.0 ? warm_up_s + std::fmod(start[k] - warm_up_s, turn_s) : warm_up_s;
        w.shift_s = start[k] - w.log_from_s;
        // The last window ends at the duration; the others where the next begins.
        const double end = k + 1 == n ? duration_s : start[k + 1];
        w.run_to_s = end - w.shift_s;
        if (!(w.run_to_s > w.log_from_s)) return std::nullopt;
        plan.windows.push_back(w);
    }
    return plan;
}

double first_pilot_s(double duration_s, int replicas) { return duration_s / (64.0 * replicas); }
double last_pilot_s(double duration_s, int replicas) { return duration_s / (2.0 * replicas); }

}  // namespace peensim
