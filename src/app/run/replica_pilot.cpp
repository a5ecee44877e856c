#include "app/run/replica_pilot.h"

#include <sstream>

#include "analysis/warm_up.h"

namespace peensim {

ReplicaPilot::ReplicaPilot(const Model& model, int replicas, std::function<void(const ReplicaPlan&)> start,
                           std::function<void(const std::string&)> give_up)
    : model_(model),
      replicas_(replicas),
      start_(std::move(start)),
      give_up_(std::move(give_up)),
      pilot_s_(first_pilot_s(model.duration_s, replicas)) {}

void ReplicaPilot::after_step(const Simulation& sim, const std::vector<ImpactRecord>& impacts) {
    if (settled_) return;
    for (const ImpactRecord& r : impacts) times_s_.push_back(r.time_s);
    const double now = sim.state().time.seconds();
    while (!settled_ && !(now < pilot_s_)) {
        if (times_s_.size() >= kPilotImpacts) {
            if (const std::optional<WarmUp> w = measure_warm_up(times_s_, pilot_s_)) {
                settled_ = true;
                if (const auto plan = plan_replicas(model_.duration_s, replicas_, now, w->warm_up_s, turn_period_s(model_), model_.seed)) {
                    start_(*plan);
                } else {
                    std::ostringstream why;
                    why << "the start-up transient (" << w->warm_up_s << " s, measured at " << now << " s) leaves no time to share out in "
                        << model_.duration_s << " s";
                    give_up_(why.str());
                }
                break;
            }
        }
        pilot_s_ *= 2.0;
        if (pilot_s_ > last_pilot_s(model_.duration_s, replicas_)) {
            settled_ = true;
            std::ostringstream why;
            why << "no steady impact rate was found in the first " << now << " s (" << times_s_.size() << " impacts; at least "
                << kPilotImpacts << " and a transient in the first half are needed)";
            give_up_(why.str());
        }
    }
    if (settled_) times_s_ = {};
}

}  // namespace peensim
