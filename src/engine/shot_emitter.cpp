#include "engine/shot_emitter.h"

#include <algorithm>
#include <limits>

#include "engine/law_input.h"

namespace peensim {

namespace {

// Draws of one emission before it is placed where the last one fell: at the flows air nozzles give
// (a few % of the exit section's volume filled with shot) a draw overlaps an earlier shot about once
// in a hundred, so 32 failing draws mean a source too crowded to be physical; the scheme then
// separates the pair as any overlap (counted in shot_overlap_corrections).
constexpr unsigned kDrawsPerEmission = 32;

}  // namespace

bool ShotEmitter::overlaps_a_shot(const SimulationState& state, const Vec3& p, double radius_m) const {
    const ShotArrays& shots = state.shots;
    for (std::size_t i = 0; i < shots.size(); ++i) {
        if (!shots.active[i]) continue;
        const double reach = radius_m + shot_radius(model_, shots, i);
        if ((shots.position(i) - p).squaredNorm() < reach * reach) return true;
    }
    return false;
}

void ShotEmitter::place_clear_of_others(const SimulationState& state, const Due& d, Vec3& p, Vec3& v) const {
    const double now = state.time.seconds();
    Emission e = d.emission;
    const ShotSize& size = model_.shot_sizes[static_cast<std::size_t>(e.size)];
    for (unsigned attempt = 1;; ++attempt) {
        p = e.position_m, v = e.velocity_m_per_s;
        size.flight->advance(p, v, now - d.time_s);
        if (attempt == kDrawsPerEmission || !overlaps_a_shot(state, p, size.radius_m)) return;
        e = *model_.sources[d.source]->emission(d.index, attempt);
    }
}

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
            due_.push_back({e->time_s, s, k, *e});
    }
    if (due_.empty()) return;
    std::stable_sort(due_.begin(), due_.end(), [](const Due& a, const Due& b) { return a.time_s < b.time_s; });
    ShotArrays& shots = state.shots;
    std::size_t slot = 0;  // the lowest inactive slot is searched from here on
    for (const Due& d : due_) {
        while (slot < shots.size() && shots.active[slot]) ++slot;
        if (slot == shots.size()) shots.grow(shots.size() + 1);  // std::vector's growth is amortised
        Vec3 p, v;
        place_clear_of_others(state, d, p, v);
        shots.set_position(slot, p);
        shots.set_velocity(slot, v);
        // A new shot does not spin: a slot freed by a collected shot kept that shot's spin, and
        // the soft scheme's next contact began with it (oblique rebounds kept 0.9-0.97 of their
        // tangential speed instead of a gripping sphere's 5/7).
        shots.set_spin(slot, Vec3::Zero());
        shots.active[slot] = 1;
        shots.size_class[slot] = static_cast<unsigned char>(d.emission.size);
        if (static_cast<std::size_t>(d.emission.size) < state.shots_per_size.size())
            ++state.shots_per_size[static_cast<std::size_t>(d.emission.size)];
        shots.in_flight[slot] = 1;
        state.fastest_shot_m_per_s = std::max(state.fastest_shot_m_per_s, v.norm());
        added.push_back(static_cast<int>(slot));
    }
}

}  // namespace peensim
