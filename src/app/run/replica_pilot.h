// Replica 0's pilot (app/run/replica_plan.h): listens to the run's first impacts and, at pilot
// times that double from first_pilot_s(), measures the start-up transient (MSER-5). Once it is found
// among at least kPilotImpacts impacts, the plan of the replicas is handed to `start`; past
// last_pilot_s() without one, the run goes on as one replica and `give_up` hears why.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "app/run/replica_plan.h"
#include "engine/run_loop.h"

namespace peensim {

class ReplicaPilot final : public RunListener {
public:
    ReplicaPilot(const Model& model, int replicas, std::function<void(const ReplicaPlan&)> start,
                 std::function<void(const std::string&)> give_up);

    // Each pilot time is a pause: the warm-up is measured at exactly that time.
    double pause_at_s() const override { return settled_ ? std::numeric_limits<double>::infinity() : pilot_s_; }
    void after_step(const Simulation& sim, const std::vector<ImpactRecord>& impacts) override;

private:
    const Model& model_;
    int replicas_;
    std::function<void(const ReplicaPlan&)> start_;
    std::function<void(const std::string&)> give_up_;
    std::vector<double> times_s_;  // s, the logged impacts' times so far
    double pilot_s_;               // s, the next time to look
    bool settled_ = false;         // planned, or given up
};

}  // namespace peensim
