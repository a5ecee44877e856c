// A model, its mutable state and the stepping scheme that advances it. No I/O: impacts go to a
// buffer the caller drains after each step (app/run/run_job writes them).
#pragma once

#include <algorithm>
#include <limits>
#include <memory>
#include <vector>

#include "engine/shot_emitter.h"
#include "engine/simulation_state.h"
#include "engine/stepper.h"
#include "model/model.h"
#include "model/shot_placement.h"

namespace peensim {

class Simulation {
public:
    // A fresh run: shot placed on the sonotrode from the model's seed (throws InputError if they
    // do not fit or the chamber is open).
    explicit Simulation(std::shared_ptr<const Model> model);
    // A fresh run from shot already placed (a run places them in the cavity its setup check built).
    Simulation(std::shared_ptr<const Model> model, const InitialShots& shots);
    // A resumed run from a saved state.
    Simulation(std::shared_ptr<const Model> model, SimulationState state);

    // One unit of work of the scheme (a time step, or a stretch of events); impacts on logged
    // components are appended to `impacts`. An event-driven scheme stops exactly at `pause_at_s`
    // (s) if it comes first (see Stepper::advance); a pause not after the present is ignored.
    // The sources' shot due by then join the state (ShotEmitter), the scheme told of them.
    void step(std::vector<ImpactRecord>& impacts, double pause_at_s = std::numeric_limits<double>::infinity());
    bool finished() const { return !(state_.time.seconds() < end_s_); }
    // Ends the run at t_s (s) instead of the scene's duration (a replica's window: app/run/replica_plan.h);
    // never past the duration.
    void end_at(double t_s) { end_s_ = std::min(t_s, model_->duration_s); }
    double end_s() const { return end_s_; }  // s, where finished() is true
    // A checkpoint of the state now resumes into exactly this run (Stepper::at_restart_point).
    bool at_restart_point() const { return scheme_->at_restart_point(); }

    const Model& model() const { return *model_; }
    const SimulationState& state() const { return state_; }
    // Changes the state (place a shot, set the time) between steps: edit(SimulationState&) runs on
    // the true state, and the scheme goes on from the result. The only way to change the state:
    // a scheme that keeps flights beside it (event-driven) would otherwise overwrite an edit.
    template <class Edit>
    void edit_state(Edit&& edit) {
        edit(state_);
        scheme_->state_changed();
    }
    const Stepper& scheme() const { return *scheme_; }

private:
    std::shared_ptr<const Model> model_;
    SimulationState state_;
    std::unique_ptr<Stepper> scheme_;
    ShotEmitter emitter_;
    double end_s_ = 0.0;        // s, the scene's duration unless end_at() moved it
    std::vector<int> emitted_;  // scratch: the slots of the shot just emitted

    void emit_due();  // the emissions at or before the state's time
};

}  // namespace peensim
