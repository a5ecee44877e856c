// Small helpers the engine tests use to report a run: wall time and the non-zero health counters.
#pragma once

#include <chrono>
#include <string>

#include "engine/simulation_state.h"

namespace peensim::testing {

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// "name count; " for every health counter.
inline std::string health_text(const HealthCounters& h) {
    std::string s;
    h.for_each([&](const char* name, std::uint64_t n) { s += std::string(name) + " " + std::to_string(n) + "; "; });
    return s;
}

}  // namespace peensim::testing
