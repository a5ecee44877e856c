// The event scheme (`accuracy.scheme: event`): the event core (event_core.h: exact flights, exact
// collision times, rigid contact laws) between restart points, and a load mostly at rest handed to
// time stepping, whose sustained contacts resolve whole piles at once where events would crawl
// through them shot by shot.
#pragma once

#include <memory>
#include <vector>

#include "engine/event/event_core.h"
#include "engine/stepper.h"
#include "model/model.h"

namespace peensim {

class EventStepping final : public Stepper {
public:
    explicit EventStepping(std::shared_ptr<const Model> model);
    ~EventStepping() override;

    std::string_view name() const override { return "event"; }
    // Processes the events up to min(t_end_s, pause_at_s, now + kSyncInterval) and leaves the
    // state (positions, velocities) exact at that time. Where it pauses does not change the run.
    void advance(SimulationState& state, double t_end_s, double pause_at_s, std::vector<ImpactRecord>& impacts) override;
    // Its own work, plus the time stepping's of the intervals handed over.
    const StepStats& stats() const override;
    // Every EventCore::kRestartInterval of simulated time the scheme starts afresh from the state
    // alone, exactly as a run resumed from a checkpoint of that state does (event_core.h): so a
    // resumed run equals the uninterrupted one, byte for byte. Restart points come at least every
    // few tenths of a second of wall time: checkpoints and interrupts wait for one.
    bool at_restart_point() const override { return !core_.started(); }
    // Starts afresh from the edited state at the next advance(), as at a restart point.
    void state_changed() override;
    // Predicts the new shot's flights at once (the scheme stopped at their emission time).
    void shots_added(SimulationState& state, const std::vector<int>& shots) override;

    // Hand-over to time stepping: at a restart point, when more than this fraction of the shot lie
    // still (slower than kHandOverSpeed, m/s) on a surface, the next interval is time-stepped.
    static constexpr double kHandOverFraction = 0.1;
    static constexpr double kHandOverSpeed = 0.05;

private:
    std::shared_ptr<const Model> model_;
    EventCore core_;
    mutable StepStats combined_;          // stats(): the core's plus the handed-over time stepping's
    bool handed_over_ = false;            // this interval is time-stepped
    std::unique_ptr<Stepper> hand_over_;  // the scheme a load at rest is handed to (time stepping), built at the first hand-over
};

}  // namespace peensim
