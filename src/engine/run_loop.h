// The one run loop: advances a Simulation to the scene's end, or until asked to stop, and hands
// every step's impacts and every restart point to listeners (the impact writer, the recorder of a
// video, the progress bar, checkpoints; a benchmark's statistics; a test's tallies). `run`,
// `bench`, the bench binary and the tests drive the engine through it, so a new front end (a
// sweep runner, a language binding) adds a listener instead of another loop.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "engine/impact_record.h"
#include "engine/simulation.h"

namespace peensim {

class RunListener {
public:
    virtual ~RunListener() = default;
    // Once, before the first step (the state is the run's start, or the resumed checkpoint's).
    virtual void at_start(const Simulation& /*sim*/) {}
    // The latest time (s) the next step may end at (the event-driven scheme stops exactly there:
    // a video frame's time); +infinity: wherever the scheme likes.
    virtual double pause_at_s() const { return std::numeric_limits<double>::infinity(); }
    // After every step: the impacts on logged components it produced (valid during the call only)
    // and the simulation (its state is the true state at the step's end).
    virtual void after_step(const Simulation& /*sim*/, const std::vector<ImpactRecord>& /*impacts*/) {}
    // At each restart point (a checkpoint of the state now resumes into exactly this run: every
    // step of time stepping, each restart interval of the event-driven scheme).
    virtual void at_restart_point(const Simulation& /*sim*/) {}
    // Whether the run has what it came for (run until coverage): asked at each restart point, after
    // at_restart_point; yes ends the run there as finished, before the scene's duration.
    virtual bool done() const { return false; }
    // The run ends: interrupted (a stop was asked: the state is a restart point, a clean place to
    // checkpoint and resume from) or finished (the scene's end, or a listener is done). Exactly one
    // of the two is called, once, after the last step (and its restart point's calls).
    virtual void at_interrupt(const Simulation& /*sim*/) {}
    virtual void at_finish(const Simulation& /*sim*/) {}
};

class RunLoop {
public:
    explicit RunLoop(Simulation& sim) : sim_(sim) { impacts_.reserve(4096); }

    // Listeners are called in the order they were added; they must outlive the loop's run().
    void add(RunListener& listener) { listeners_.push_back(&listener); }

    // Runs to the scene's end, or to a restart point where a listener is done: true. `stop`, asked
    // after every step with the number of steps taken, ends the run at the next restart point once
    // it has said yes: false (the state there is a clean place to checkpoint and resume from).
    // Listeners hear at_start first, and at_finish or at_interrupt last.
    bool run(const std::function<bool(std::uint64_t steps)>& stop = {}) {
        for (RunListener* l : listeners_) l->at_start(sim_);
        const bool finished = steps_until_end(stop);
        for (RunListener* l : listeners_) finished ? l->at_finish(sim_) : l->at_interrupt(sim_);
        return finished;
    }

private:
    bool steps_until_end(const std::function<bool(std::uint64_t steps)>& stop) {
        std::uint64_t steps = 0;
        bool stopping = false;
        while (!sim_.finished()) {
            double pause_at_s = std::numeric_limits<double>::infinity();
            for (const RunListener* l : listeners_) pause_at_s = std::min(pause_at_s, l->pause_at_s());
            sim_.step(impacts_, pause_at_s);
            for (RunListener* l : listeners_) l->after_step(sim_, impacts_);
            impacts_.clear();
            ++steps;
            stopping = stopping || (stop && stop(steps));
            if (!sim_.at_restart_point()) continue;
            if (stopping) return false;
            for (RunListener* l : listeners_) l->at_restart_point(sim_);
            for (const RunListener* l : listeners_)
                if (l->done()) return true;
        }
        return true;
    }

    Simulation& sim_;
    std::vector<RunListener*> listeners_;
    std::vector<ImpactRecord> impacts_;  // one step's, consumed by the listeners, never kept
};

}  // namespace peensim
