// A resumable snapshot of a run: the simulation state, how far impacts.csv.partial got, and the
// running statistics. Written atomically (never half a file) every checkpoint interval and when
// a run is interrupted; `peensim run --resume` continues from it exactly as if never stopped.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/checkpoint/field_list.h"
#include "engine/simulation_state.h"
#include "model/model.h"
#include "output/speed_histogram.h"

namespace peensim {

inline constexpr const char* kCheckpointFileName = "checkpoint.bin";

struct Checkpoint {
    std::uint64_t scene_hash = 0;  // must match the scene being resumed
    SimulationState state;
    std::uint64_t csv_bytes = 0;  // bytes of impacts.csv.partial that belong to this state
    std::uint64_t csv_rows = 0;
    std::vector<SpeedHistogram> normal_speeds;  // per logged component, in component order
    double wall_time_s = 0.0;                   // s, wall time spent before this checkpoint
    // A run until coverage as replicas (app/run/replica_rounds.h), which resumes as replica 0 alone:
    // the time added to its impacts (its slot's place in the run), and the other replicas' impacts
    // and slow contacts in the slots logged (summary entries: shot-shot, then each component).
    double log_shift_s = 0.0;  // s
    std::vector<std::uint64_t> replica_impacts;
    std::vector<std::uint64_t> replica_slow_contacts;
};

// Every field's name and the format version that added it, in file order (checkpoint_fields.h).
std::vector<FieldName> checkpoint_field_names();
// The file ends with a checksum of everything before it.
void save_checkpoint(const std::string& path, const Checkpoint& checkpoint);
// Throws std::runtime_error if the file is missing; InputError (exit 2) if it is not a checkpoint,
// of another version, truncated or damaged (checksum).
Checkpoint load_checkpoint(const std::string& path);
// Throws InputError unless `checkpoint` can resume `model`: the same scene (settings that do not
// change the physics aside), a time within the run, every shot's state finite and inside the
// assembly, counters and statistics for the scene's components.
void check_resumable(const std::string& path, const Checkpoint& checkpoint, const Model& model, std::size_t logged_components);

}  // namespace peensim
