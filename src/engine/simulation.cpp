#include "engine/simulation.h"

#include "engine/event/event_stepping.h"
#include "engine/law_input.h"
#include "engine/time_stepping.h"

namespace peensim {

namespace {

std::unique_ptr<Stepper> make_scheme(const std::shared_ptr<const Model>& model) {
    switch (model->scheme) {
        case SteppingScheme::step: return std::make_unique<TimeStepping>(model);
        case SteppingScheme::event: return std::make_unique<EventStepping>(model);
    }
    return std::make_unique<TimeStepping>(model);
}

SimulationState initial_state(const Model& model, const InitialShots& shots) {
    SimulationState state;
    state.shots.resize(static_cast<std::size_t>(model.shot_count));
    for (std::size_t i = 0; i < shots.positions.size(); ++i) {
        state.shots.set_position(i, shots.positions[i]);
        state.shots.set_velocity(i, shots.velocities[i]);
        state.fastest_shot_m_per_s = std::max(state.fastest_shot_m_per_s, shots.velocities[i].norm());
    }
    state.impacts_per_component.assign(model.components.size(), 0);
    state.slow_contacts_per_component.assign(model.components.size(), 0);
    state.law_state = fresh_law_state(model);
    return state;
}

}  // namespace

Simulation::Simulation(std::shared_ptr<const Model> model)
    : model_(std::move(model)), state_(initial_state(*model_, place_shots(*model_))), scheme_(make_scheme(model_)) {}

Simulation::Simulation(std::shared_ptr<const Model> model, const InitialShots& shots)
    : model_(std::move(model)), state_(initial_state(*model_, shots)), scheme_(make_scheme(model_)) {}

Simulation::Simulation(std::shared_ptr<const Model> model, SimulationState state)
    : model_(std::move(model)), state_(std::move(state)), scheme_(make_scheme(model_)) {}

}  // namespace peensim
