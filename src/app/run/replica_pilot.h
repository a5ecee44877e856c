// Replica 0's pilot (app/run/replica_plan.h, replica_rounds.h): listens to the run's first impacts
// and, at pilot times that double from a first one, measures the start-up transient (MSER-5).
// Once it is found among at least kPilotImpacts impacts, the reading is handed to `start`, which
// plans the replicas (or says why it cannot); past the last pilot time without one, or when
// `start` cannot plan, the run goes on as one replica and `give_up` hears why.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "app/run/replica_plan.h"
#include "engine/run_loop.h"

namespace peensim {

struct PilotReading {
    double pilot_s = 0.0;       // s, replica 0's time now
    double warm_up_s = 0.0;     // s, the measured start-up transient
    std::uint64_t impacts = 0;  // logged impacts up to pilot_s
};

class ReplicaPilot final : public RunListener {
public:
    // start: plans from the reading; nullopt when it did, else why it could not.
    ReplicaPilot(double first_pilot_s, double last_pilot_s, std::function<std::optional<std::string>(const PilotReading&)> start,
                 std::function<void(const std::string&)> give_up);

    // Each pilot time is a pause: the warm-up is measured at exactly that time.
    double pause_at_s() const override { return settled_ ? std::numeric_limits<double>::infinity() : pilot_s_; }
    void after_step(const Simulation& sim, const std::vector<ImpactRecord>& impacts) override;

private:
    std::function<std::optional<std::string>(const PilotReading&)> start_;
    std::function<void(const std::string&)> give_up_;
    std::vector<double> times_s_;  // s, the logged impacts' times so far
    double pilot_s_;               // s, the next time to look
    double last_pilot_s_;          // s, the last
    bool settled_ = false;         // planned, or given up
};

// The one-run plan (replica_plan.h) from a reading: the windows of `replicas` replicas over the
// scene's duration handed to `start`, or why the duration leaves no time to share out.
std::function<std::optional<std::string>(const PilotReading&)> plan_windows_then(const Model& model, int replicas,
                                                                                 std::function<void(const ReplicaPlan&)> start);

}  // namespace peensim
