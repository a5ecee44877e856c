#include "app/run/replica_pilot.h"

#include <sstream>

#include "analysis/warm_up.h"

namespace peensim {

ReplicaPilot::ReplicaPilot(double first_pilot_s, double last_pilot_s, std::function<std::optional<std::string>(const PilotReading&)> start,
                           std::function<void(const std::string&)> give_up)
    : start_(std::move(start)), give_up_(std::move(give_up)), pilot_s_(first_pilot_s), last_pilot_s_(last_pilot_s) {}

void ReplicaPilot::after_step(const Simulation& sim, const std::vector<ImpactRecord>& impacts) {
    if (settled_) return;
    for (const ImpactRecord& r : impacts) times_s_.push_back(r.time_s);
    const double now = sim.state().time.seconds();
    while (!settled_ && !(now < pilot_s_)) {
        if (times_s_.size() >= kPilotImpacts) {
            if (const std::optional<WarmUp> w = measure_warm_up(times_s_, pilot_s_)) {
                settled_ = true;
                if (const std::optional<std::string> why = start_(PilotReading{now, w->warm_up_s, times_s_.size()})) give_up_(*why);
                break;
            }
        }
        pilot_s_ *= 2.0;
        if (pilot_s_ > last_pilot_s_) {
            settled_ = true;
            std::ostringstream why;
            why << "no steady impact rate was found in the first " << now << " s (" << times_s_.size() << " impacts; at least "
                << kPilotImpacts << " and a transient in the first half are needed)";
            give_up_(why.str());
        }
    }
    if (settled_) times_s_ = {};
}

std::function<std::optional<std::string>(const PilotReading&)> plan_windows_then(const Model& model, int replicas,
                                                                                 std::function<void(const ReplicaPlan&)> start) {
    return [&model, replicas, start = std::move(start)](const PilotReading& r) -> std::optional<std::string> {
        if (const auto plan = plan_replicas(model.duration_s, replicas, r.pilot_s, r.warm_up_s, turn_period_s(model), model.seed)) {
            start(*plan);
            return std::nullopt;
        }
        std::ostringstream why;
        why << "the start-up transient (" << r.warm_up_s << " s, measured at " << r.pilot_s << " s) leaves no time to share out in "
            << model.duration_s << " s";
        return why.str();
    };
}

}  // namespace peensim
