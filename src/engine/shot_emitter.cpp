#include "engine/shot_emitter.h"

#include <algorithm>
#include <limits>

namespace peensim {

double ShotEmitter::next_time(const SimulationState& state) const {
    double next = std::numeric_limits<double>::infinity();
    for (std::size_t s = 0; s < model_.sources.size(); ++s)
        if (const auto e = model_.sources[s]->emission(state.emitted_per_source[s])) next = std::min(next, e->time_s);
    return next;
}

void ShotEmitter::emit_due(SimulationState& state, std::vector<int>& added) {
    added.clear();
    if (model_.sources.empty()) return;
    const double now = state.time.seconds();
    due_.clear();
    for (std::size_t s = 0; s < model_.sources.size(); ++s) {
        std::uint64_t& k = state.emitted_per_source[s];
        for (auto e = model_.sources[s]->emission(k); e && e->time_s <= now; e = model_.sources[s]->emission(++k))
            due_.push_back({e->time_s, s, *e});
    }
    if (due_.empty()) return;
    std::stable_sort(due_.begin(), due_.end(), [](const Due& a, const Due& b) { return a.time_s < b.time_s; });
    ShotArrays& shots = state.shots;
    std::size_t slot = 0;  // the lowest inactive slot is searched from here on
    for (const Due& d : due_) {
        while (slot < shots.size() && shots.active[slot]) ++slot;
        if (slot == shots.size()) shots.grow(shots.size() + 1);  // std::vector's growth is amortised
        Vec3 p = d.emission.position_m, v = d.emission.velocity_m_per_s;
        model_.flight->advance(p, v, now - d.time_s);
        shots.set_position(slot, p);
        shots.set_velocity(slot, v);
        shots.active[slot] = 1;
        shots.in_flight[slot] = 1;
        state.fastest_shot_m_per_s = std::max(state.fastest_shot_m_per_s, v.norm());
        added.push_back(static_cast<int>(slot));
    }
}

}  // namespace peensim
