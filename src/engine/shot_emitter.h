// Puts the shot the model's sources emit into the state, at their emission times: each takes the
// lowest inactive slot (a collected or lost shot's), else a new one at the end, and flies from its
// emission to the state's time (nothing when the scheme stopped exactly there, as the event-driven
// scheme does; up to one step of time stepping, a quarter radius of travel, otherwise).
#pragma once

#include <vector>

#include "engine/simulation_state.h"
#include "model/model.h"

namespace peensim {

class ShotEmitter {
public:
    explicit ShotEmitter(const Model& model) : model_(model) {}

    // s, absolute: the earliest emission still to come (+infinity: none).
    double next_time(const SimulationState& state) const;
    // Emits every emission at or before the state's time, in time order (ties: the source listed
    // first); `added` gets their slots. Counts them in state.emitted_per_source.
    void emit_due(SimulationState& state, std::vector<int>& added);

private:
    struct Due {
        double time_s;
        std::size_t source;
        Emission emission;
    };
    const Model& model_;
    std::vector<Due> due_;  // scratch, reused
};

}  // namespace peensim
