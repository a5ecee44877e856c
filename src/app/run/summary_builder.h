// Builds the run summary (summary.json, the text printed at the end, the benchmark's figures)
// from a simulation's state and timing.
#pragma once

#include <string>
#include <vector>

#include "engine/simulation.h"
#include "output/run_summary.h"
#include "output/speed_histogram.h"

namespace peensim {

// The model's scene hash as summary.json writes it (16 hex digits).
std::string scene_hash_text(const Model& model);

// normal_speeds: one histogram per logged component, in component order.
RunSummary build_summary(const Simulation& sim, const std::string& scene_file, const std::vector<SpeedHistogram>& normal_speeds,
                         double wall_time_s, bool finished);

}  // namespace peensim
