#include "engine/simulation.h"

#include "engine/law_input.h"

namespace peensim {

namespace {

SimulationState initial_state(const Model& model, const InitialShots& shots) {
    SimulationState state;
    state.shots.resize(static_cast<std::size_t>(model.shot_count));
    for (std::size_t i = 0; i < shots.positions.size(); ++i) {
        state.shots.set_position(i, shots.positions[i]);
        state.shots.set_velocity(i, shots.velocities[i]);
        if (i < shots.sizes.size()) state.shots.size_class[i] = static_cast<unsigned char>(shots.sizes[i]);
        // Placed apart from every surface and from each other: each starts in a free flight, whose
        // end in a contact slower than the impact line is a slow contact in every scheme (the
        // contact policy's counting rule; time stepping saw it after a first step touching nothing,
        // the event-driven schemes never).
        state.shots.in_flight[i] = 1;
        state.fastest_shot_m_per_s = std::max(state.fastest_shot_m_per_s, shots.velocities[i].norm());
    }
    state.impacts_per_component.assign(model.components.size(), 0);
    state.slow_contacts_per_component.assign(model.components.size(), 0);
    state.law_state = fresh_law_state(model);
    state.emitted_per_source.assign(model.sources.size(), 0);
    state.collected_per_sink.assign(model.sinks.size(), 0);
    state.shots_per_size.assign(model.shot_sizes.size(), 0);
    for (std::size_t i = 0; i < shots.positions.size(); ++i) ++state.shots_per_size[state.shots.size_class[i]];
    return state;
}

}  // namespace

Simulation::Simulation(std::shared_ptr<const Model> model)
    : model_(std::move(model)),
      state_(initial_state(*model_, place_shots(*model_))),
      scheme_(make_stepper(model_)),
      emitter_(*model_),
      end_s_(model_->duration_s) {}

Simulation::Simulation(std::shared_ptr<const Model> model, const InitialShots& shots)
    : model_(std::move(model)),
      state_(initial_state(*model_, shots)),
      scheme_(make_stepper(model_)),
      emitter_(*model_),
      end_s_(model_->duration_s) {}

Simulation::Simulation(std::shared_ptr<const Model> model, SimulationState state)
    : model_(std::move(model)), state_(std::move(state)), scheme_(make_stepper(model_)), emitter_(*model_), end_s_(model_->duration_s) {
    // A state made by hand (a test) may leave the sources' and sinks' counts out.
    state_.emitted_per_source.resize(model_->sources.size(), 0);
    state_.collected_per_sink.resize(model_->sinks.size(), 0);
}

void Simulation::step(std::vector<ImpactRecord>& impacts, double pause_at_s) {
    emit_due();
    const double now = state_.time.seconds();
    // The next emission is a pause too: the event-driven scheme stops exactly there, so the shot
    // starts exactly at its emission time (time stepping steps past it: see ShotEmitter).
    pause_at_s = std::min(pause_at_s, emitter_.next_time(state_));
    // A pause at or before the present is no pause (asked again and again, it would stall the run).
    if (!(pause_at_s > now)) pause_at_s = std::numeric_limits<double>::infinity();
    scheme_->advance(state_, end_s_, pause_at_s, impacts);
    emit_due();
}

void Simulation::emit_due() {
    emitter_.emit_due(state_, emitted_);
    if (!emitted_.empty()) scheme_->shots_added(state_, emitted_);
}

}  // namespace peensim
