// `peensim run` in-process for tests: the options a test varies, and what the run printed.
#pragma once

#include <cstdint>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app/run/run_job.h"

namespace peensim::testing {

struct InProcessRun {
    std::string scene_path;
    std::string output_dir;
    bool resume = false;
    bool analyze = false;                           // the tests that use this look at the run's own outputs
    std::optional<std::uint64_t> stop_after_steps;  // then an interrupted run (kExitInterrupted)
    std::vector<std::string> overrides;             // --set
    int replicas = 1;                               // --replicas
};

struct InProcessResult {
    int code = -1;
    std::string out, err;
};

inline InProcessResult run_in_process(const InProcessRun& r) {
    RunOptions o;
    o.scene_path = r.scene_path;
    o.output_dir = r.output_dir;
    o.progress = false;
    o.analyze = r.analyze;
    o.resume = r.resume;
    o.stop_after_steps = r.stop_after_steps;
    o.overrides = r.overrides;
    o.replicas = r.replicas;
    std::ostringstream out, err;
    InProcessResult result;
    result.code = run_job(o, out, err);
    result.out = out.str();
    result.err = err.str();
    return result;
}

}  // namespace peensim::testing
