// A resumable snapshot of a run: the simulation state, how far impacts.csv.partial got, and the
// running statistics. Written atomically (never half a file) every checkpoint interval and when
// a run is interrupted; `peensim run --resume` continues from it exactly as if never stopped.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/simulation_state.h"
#include "output/speed_histogram.h"

namespace peensim {

inline constexpr const char* kCheckpointFileName = "checkpoint.bin";

struct Checkpoint {
    std::uint64_t scene_hash = 0;       // must match the scene being resumed
    SimulationState state;
    std::uint64_t csv_bytes = 0;        // bytes of impacts.csv.partial that belong to this state
    std::uint64_t csv_rows = 0;
    std::vector<SpeedHistogram> normal_speeds;  // per logged component, in component order
    double wall_time_s = 0.0;           // s, wall time spent before this checkpoint
};

void save_checkpoint(const std::string& path, const Checkpoint& checkpoint);
// Throws std::runtime_error if the file is missing, truncated or of another version.
Checkpoint load_checkpoint(const std::string& path);

}  // namespace peensim
