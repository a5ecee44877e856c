// The tests drive the engine through the product's run loop (engine/run_loop.h), the path `run`,
// `bench` and the bench binary take, instead of stepping Simulation by hand: a hand-written loop is
// a second run loop that can drift from the real one (the pauses listeners ask for, the end at a
// restart point, the hooks). A test says what it watches as hooks; RunLoop does the stepping.
// (tests/architecture/check_hand_stepping.py keeps the hand loops out of the tests.)
#pragma once

#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include "engine/impact_record.h"
#include "engine/run_loop.h"
#include "engine/simulation.h"

namespace peensim::testing {

// What a test does during a run; every hook is optional (RunListener's hooks, with the simulation).
// Written with designated initializers: {.after_step = ..., .done = ...} (in this order).
struct LoopHooks {
    // After every step: the simulation (its state at the step's end) and the step's logged impacts.
    std::function<void(const Simulation&, const std::vector<ImpactRecord>&)> after_step{};
    // Before every step: the latest time (s) it may end at, given the state now (the event-driven
    // schemes stop exactly there; time stepping may step past it). Unset: no pause.
    std::function<double(const Simulation&)> pause_at_s{};
    // At each restart point: every step of time stepping, the event-driven schemes' restart interval
    // (EventCore::kRestartInterval, 0.1 s) or work budget, whichever comes first.
    std::function<void(const Simulation&)> at_restart_point{};
    // Asked at each restart point, after at_restart_point: yes ends the run there. Between restart
    // points it is not asked, so only time stepping ends right after the step it says yes to.
    std::function<bool(const Simulation&)> done{};
};

// A pause every period_s (s) after the state's time: the event-driven schemes then stop at least
// that often, and a test looks at the state there (audits, invariants).
inline std::function<double(const Simulation&)> pause_every(double period_s) {
    return [period_s](const Simulation& sim) { return sim.state().time.seconds() + period_s; };
}

// The hooks as a RunLoop listener.
class HookListener final : public RunListener {
public:
    explicit HookListener(LoopHooks hooks) : hooks_(std::move(hooks)) {}
    void at_start(const Simulation& sim) override { sim_ = &sim; }
    double pause_at_s() const override { return hooks_.pause_at_s ? hooks_.pause_at_s(*sim_) : std::numeric_limits<double>::infinity(); }
    void after_step(const Simulation& sim, const std::vector<ImpactRecord>& impacts) override {
        if (hooks_.after_step) hooks_.after_step(sim, impacts);
    }
    void at_restart_point(const Simulation& sim) override {
        if (hooks_.at_restart_point) hooks_.at_restart_point(sim);
    }
    bool done() const override { return hooks_.done && hooks_.done(*sim_); }

private:
    LoopHooks hooks_;
    const Simulation* sim_ = nullptr;  // set at the start: pause_at_s() and done() are asked without it
};

// Every logged impact of the run, in order.
class ImpactCollector final : public RunListener {
public:
    std::vector<ImpactRecord> impacts;
    void after_step(const Simulation& /*sim*/, const std::vector<ImpactRecord>& step) override {
        impacts.insert(impacts.end(), step.begin(), step.end());
    }
};

// Runs `sim` through a RunLoop with the hooks: to the scene's end, or to a restart point where
// hooks.done says yes. Returns RunLoop::run's answer (true: finished).
inline bool run_through_loop(Simulation& sim, LoopHooks hooks = {}) {
    HookListener listener(std::move(hooks));
    RunLoop loop(sim);
    loop.add(listener);
    return loop.run();
}

// As run_through_loop; returns every logged impact of the run, in order (the hooks see each step's
// impacts as well).
inline std::vector<ImpactRecord> run_collecting_impacts(Simulation& sim, LoopHooks hooks = {}) {
    ImpactCollector collector;
    HookListener listener(std::move(hooks));
    RunLoop loop(sim);
    loop.add(collector);
    loop.add(listener);
    loop.run();
    return std::move(collector.impacts);
}

}  // namespace peensim::testing
