// Puts the shot the model's sources emit into the state, at their emission times: each takes the
// lowest inactive slot (a collected or lost shot's), else a new one at the end, and flies from its
// emission to the state's time (nothing when the scheme stopped exactly there, as the event-driven
// scheme does; up to one step of time stepping, a quarter radius of travel, otherwise). A shot
// never starts overlapping another: a draw that would is drawn again (the source's next attempt at
// the same emission), so the emissions stay a function of the seed and the run's own state.
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
        std::uint64_t index;  // the source's emission number
        Emission emission;
    };
    // A shot of radius_m (m) centred at p would overlap a shot in the run.
    bool overlaps_a_shot(const SimulationState& state, const Vec3& p, double radius_m) const;
    // Where shot d is now (p, m) and its velocity (v, m/s): its first draw clear of every shot in
    // the run, flown from its emission time to the state's time.
    void place_clear_of_others(const SimulationState& state, const Due& d, Vec3& p, Vec3& v) const;
    const Model& model_;
    std::vector<Due> due_;  // scratch, reused
};

}  // namespace peensim
