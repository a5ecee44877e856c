// The random draws of a source's emission k: a generator of its own, seeded from the scene's seed,
// the source's place in the scene, k and the attempt (counter-based: no state is carried between
// emissions, so a run resumed from a checkpoint, which keeps how many each source emitted, draws
// exactly the same shot), and the shot's size from a stream that no redraw touches.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/random.h"
#include "model/shot_flow.h"
#include "scene/shot_mix.h"

namespace peensim {

// What every kind of source has in common: its name, when and how often it emits, and what makes its
// draws its own. Emission k leaves at start + k / rate, none at or after stop.
struct EmissionPlan {
    std::string name;
    double rate_per_s = 0.0;                  // shot per second
    double start_s = 0.0;                     // s, absolute
    double stop_s = 0.0;                      // s, absolute
    std::uint64_t seed = 1;                   // the scene's seed (mixed with the source's index)
    int index = 0;                            // the source's place in the scene
    std::vector<double> size_count_fraction;  // -, per shot size (Model::size_count_fraction); empty for one size
};

// The seed of emission k's draw `attempt`: the scene's seed, the source and k mixed (Random's
// SplitMix64 seeding spreads neighbouring seeds), the attempt above bit 40 (k never gets there).
inline std::uint64_t emission_stream(const EmissionPlan& plan, std::uint64_t k, unsigned attempt) {
    return plan.seed * 0x9e3779b97f4a7c15ull ^ (static_cast<std::uint64_t>(plan.index + 1) << 48) ^
           (static_cast<std::uint64_t>(attempt) << 40) ^ k;
}

// The size of emission k (an index into the mix; 0 for one size): a stream of its own (attempt
// 255, never a redraw's: at most 32), so a redraw moves the shot but keeps its size, and a scene
// of one size draws nothing.
inline int emission_size(const EmissionPlan& plan, std::uint64_t k) {
    constexpr unsigned kSizeStream = 255;
    if (plan.size_count_fraction.size() <= 1) return 0;
    Random size_rng(emission_stream(plan, k, kSizeStream));
    return size_for_draw(plan.size_count_fraction, size_rng.uniform());
}

// Emission k's time (s, absolute), or none: the plan stops before it.
inline std::optional<double> emission_time(const EmissionPlan& plan, std::uint64_t k) {
    const double t = plan.start_s + static_cast<double>(k) / plan.rate_per_s;
    if (!(t < plan.stop_s)) return std::nullopt;
    return t;
}

// The part of a source's outline its plan gives (the rest is its kind's).
inline SourceOutline outline_of(const EmissionPlan& plan, const char* kind) {
    SourceOutline o;
    o.kind = kind;
    o.rate_per_s = plan.rate_per_s;
    o.start_s = plan.start_s;
    o.stop_s = plan.stop_s;
    return o;
}

}  // namespace peensim
