// The random draws of a source's emission k: a generator of its own, seeded from the scene's seed,
// the source's place in the scene, k and the attempt (counter-based: no state is carried between
// emissions, so a run resumed from a checkpoint, which keeps how many each source emitted, draws
// exactly the same shot), and the shot's size from a stream that no redraw touches.
#pragma once

#include <cstdint>
#include <vector>

#include "common/random.h"
#include "scene/shot_mix.h"

namespace peensim {

// The seed of emission k's draw `attempt`: the scene's seed, the source and k mixed (Random's
// SplitMix64 seeding spreads neighbouring seeds), the attempt above bit 40 (k never gets there).
inline std::uint64_t emission_stream(std::uint64_t scene_seed, int source_index, std::uint64_t k, unsigned attempt) {
    return scene_seed * 0x9e3779b97f4a7c15ull ^ (static_cast<std::uint64_t>(source_index + 1) << 48) ^
           (static_cast<std::uint64_t>(attempt) << 40) ^ k;
}

// The size of emission k (an index into the mix; 0 for one size): a stream of its own (attempt
// 255, never a redraw's: at most 32), so a redraw moves the shot but keeps its size, and a scene
// of one size draws nothing.
inline int emission_size(std::uint64_t scene_seed, int source_index, std::uint64_t k, const std::vector<double>& size_count_fraction) {
    constexpr unsigned kSizeStream = 255;
    if (size_count_fraction.size() <= 1) return 0;
    Random size_rng(emission_stream(scene_seed, source_index, k, kSizeStream));
    return size_for_draw(size_count_fraction, size_rng.uniform());
}

// Emission k's time (s, absolute) for a source emitting `rate_per_s` evenly from `start_s`.
inline double emission_time(double start_s, double rate_per_s, std::uint64_t k) { return start_s + static_cast<double>(k) / rate_per_s; }

}  // namespace peensim
