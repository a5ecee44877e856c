// What decides when contacts are found and resolved. Time stepping is the first scheme; an
// event-driven scheme (exact collision times) and a soft-sphere scheme plug in beside it with
// the same model, state, contact laws and impact buffer.
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "engine/impact_record.h"
#include "engine/simulation_state.h"
#include "engine/step_stats.h"

namespace peensim {

struct Model;

class Stepper {
public:
    virtual ~Stepper() = default;
    virtual std::string_view name() const = 0;
    // Advances the state by one unit of work, never past t_end_s (s), and appends the impacts on
    // logged components to `impacts` (the caller drains it after each call). `pause_at_s` (s) is a
    // time the caller wants to see the state at (an animation frame): a scheme whose units of work
    // are long (event-driven) stops exactly there; one whose steps are short may step past it (the
    // caller then moves the shot back along their parabolas). Pausing never changes the dynamics.
    virtual void advance(SimulationState& state, double t_end_s, double pause_at_s, std::vector<ImpactRecord>& impacts) = 0;
    virtual const StepStats& stats() const = 0;
    // Whether the state alone now determines the rest of the run: a run resumed from a checkpoint
    // of this state continues exactly as this one does. Checkpoints are written only at such
    // points. Time stepping keeps nothing else, so every step end is one.
    virtual bool at_restart_point() const { return true; }
    // The caller changed the state (Simulation::edit_state): whatever the scheme keeps besides it
    // (flights, caches) is dropped, and it goes on from the state as it now is.
    virtual void state_changed() = 0;
    // Shot were added to the state at these slots, at the state's time (a source emitted them; a
    // slot may be new, or reused from a collected or lost shot): the scheme takes them into its
    // flights from now on, without disturbing the others.
    virtual void shots_added(SimulationState& state, const std::vector<int>& shots) = 0;
};

// The model's scheme (Model::scheme): time stepping, the event scheme or the soft scheme. Defined
// in engine/schemes/make_stepper.cpp, the one file that knows every scheme: the rest of engine/
// sees this interface only, so the schemes' folders (engine/event/, engine/soft/) sit above it and
// no folder of the engine includes one above it.
std::unique_ptr<Stepper> make_stepper(const std::shared_ptr<const Model>& model);

}  // namespace peensim
