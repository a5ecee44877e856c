#include "engine/event/event_stepping.h"

#include <algorithm>

#include "engine/time_stepping.h"

namespace peensim {

EventStepping::EventStepping(std::shared_ptr<const Model> model) : model_(model), core_(std::move(model)) {}

EventStepping::~EventStepping() = default;

const StepStats& EventStepping::stats() const {
    combined_ = core_.stats();
    if (hand_over_) combined_ += hand_over_->stats();
    return combined_;
}

void EventStepping::advance(SimulationState& state, double t_end_s, double pause_at_s, std::vector<ImpactRecord>& impacts) {
    const double now_s = state.time.seconds();
    if (!(t_end_s > now_s)) return;
    if (!core_.started()) {
        core_.open_interval(now_s);
        // A load mostly at rest (sonotrode off, a chamber filled with shot) is time stepping's regime:
        // its sustained contacts resolve whole piles at once, where events would crawl through them
        // shot by shot. Decided from the state alone, so a resumed run decides the same.
        handed_over_ = core_.resting_fraction(state, kHandOverFraction, kHandOverSpeed) > kHandOverFraction;
        if (handed_over_) {
            if (!hand_over_) hand_over_ = std::make_unique<TimeStepping>(model_);
            ++core_.stats().hand_overs;
            core_.set_work_budget(std::max(EventCore::kMinWorkBudget, EventCore::kWorkPerRestart * EventCore::kWorkPerShotStep *
                                                                          static_cast<std::uint64_t>(state.shots.size())));
        } else {
            core_.start_from(state);
        }
    }
    if (handed_over_) {
        const std::uint64_t steps_before = state.shot_steps;
        hand_over_->advance(state, std::min(t_end_s, core_.next_restart_s()), pause_at_s, impacts);
        core_.count_work(EventCore::kWorkPerShotStep * (state.shot_steps - steps_before), state.time.seconds());
        if (state.time.seconds() >= core_.next_restart_s()) core_.close_interval();
        return;
    }
    const EventCore::Stop stop = core_.advance(state, t_end_s, pause_at_s, impacts);
    // Most shot in sustained contact or asleep, and the state says the load is at rest: restart at
    // this grid point, to hand the load over to time stepping (see above). Looked at on the grid only,
    // so that where a caller pauses never changes the run.
    if (!core_.started() || stop.stop_s != stop.grid_s) return;
    if (core_.still_more_than(kHandOverFraction) && core_.resting_fraction(state, kHandOverFraction, kHandOverSpeed) > kHandOverFraction)
        core_.close_interval();
}

void EventStepping::state_changed() {
    core_.close_interval();
    if (hand_over_) hand_over_->state_changed();
}

void EventStepping::shots_added(SimulationState& state, const std::vector<int>& shots) {
    core_.fit_shots(state.shots.size());
    if (hand_over_) hand_over_->shots_added(state, shots);
    // Between restart points (or time-stepped) nothing is kept that a new shot could upset: the
    // next start takes it from the state with the others.
    if (!core_.started() || handed_over_) return;
    core_.take_new_shots(state, shots);
}

}  // namespace peensim
