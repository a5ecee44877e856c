// Where to stop a run until coverage as replicas so that the stop comes in replica 0's second slot
// (app/run/replica_rounds.h), from the summary of the same run left to finish.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>

namespace peensim {

// The steps (the event scheme's, 1 ms of simulated time each) from the start to halfway through the
// part of replica 0's second slot the finished run logged. Its first slot is [0, A) in both clocks;
// its second starts at A in its own clock and where replica 1's first slot ends in the run's.
inline std::uint64_t steps_into_second_slot(const nlohmann::json& summary) {
    const auto& windows = summary["replicas"]["windows"];
    const double a = windows[0]["end_s"].get<double>();
    const double second_from = windows[1]["end_s"].get<double>();
    const double second_to = windows.size() > 2 ? windows[2]["end_s"].get<double>() : summary["simulated_time_s"].get<double>();
    return static_cast<std::uint64_t>(std::lround(1000.0 * (a + 0.5 * (second_to - second_from))));
}

}  // namespace peensim
