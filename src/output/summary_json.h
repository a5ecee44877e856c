// summary.json: the machine-readable end-of-run report. Keys carry their unit (_s, _mps,
// _bytes); NaN (statistics of a component without impacts) is written as null.
//
// {
//   "scene_file": "...", "scene_hash": "...", "scheme": "...", "finished": true,
//   "simulated_time_s": ..., "duration_s": ..., "wall_time_s": ...,
//   "steps": ..., "shot_steps": ..., "shot_steps_per_s": ..., "sim_seconds_per_wall_second": ...,
//   "shot_count": ..., "shot_lost": ...,
//   "impacts_per_component": [{"component": "gear", "impacts": 123}, ...],
//   "slow_contacts_per_component": [{"component": "gear", "slow_contacts": 4}, ...],
//   "impact_speed_mps": 0.05,
//   "normal_speed": [{"component": "gear", "count": 123, "mean_normal_speed_mps": ...,
//                     "p10_normal_speed_mps": ..., "p50_normal_speed_mps": ...,
//                     "p90_normal_speed_mps": ..., "max_normal_speed_mps": ...}, ...],
//   "health_counters": {"<counter>": 0, ...},
//   "first_search_fallback": {"time_s": .., "shot": .., "component": "..", "position_m": [x, y, z]}  (only after one),
//   "step_stage_time_s": {"<stage>": 1.25, ...},
//   "peak_memory_bytes": ...
// }
#pragma once

#include <string>

#include "output/run_summary.h"

namespace peensim {

// Pretty-printed JSON (2-space indent, keys in the order above), ending with a newline.
std::string summary_to_json(const RunSummary& summary);

// Writes summary_to_json(summary) to `path` atomically; throws std::runtime_error on failure.
void write_summary(const std::string& path, const RunSummary& summary);

}  // namespace peensim
