// What decides when contacts are found and resolved. Time stepping is the first scheme; an
// event-driven scheme (exact collision times) and a soft-sphere scheme plug in beside it with
// the same model, state, contact laws and impact buffer.
#pragma once

#include <string_view>
#include <vector>

#include "engine/simulation_state.h"
#include "engine/step_stats.h"
#include "output/impact_record.h"

namespace peensim {

class Stepper {
public:
    virtual ~Stepper() = default;
    virtual std::string_view name() const = 0;
    // Advances the state by one unit of work (one step), never past t_end_s (s), and appends
    // the impacts on logged components to `impacts` (the caller drains it after each call).
    virtual void advance(SimulationState& state, double t_end_s, std::vector<ImpactRecord>& impacts) = 0;
    virtual const StepStats& stats() const = 0;
};

}  // namespace peensim
