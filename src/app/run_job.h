// `peensim run`: scene file -> model -> simulation, streaming impacts.csv, writing
// summary.json and the resolved scene, checkpointing for resume, reporting progress.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "app/checkpoint_cadence.h"

namespace peensim {

struct RunOptions {
    std::string scene_path;
    std::vector<std::string> overrides;                // --set path=value
    std::string output_dir;                            // -o; "" = the scene's output.directory, else out/<scene name>
    bool progress = true;                              // draw a progress bar (only on a terminal)
    bool resume = false;                               // continue from output_dir/checkpoint.bin
    bool strict = false;                               // fail (exit 3) if a serious health counter is non-zero
    bool analyze = true;                               // run `peensim analyze` on the outputs when the run finishes
    std::optional<bool> render;                        // --render / --no-render; empty = as the scene's `render` block says
    std::optional<std::uint64_t> stop_after_steps;     // interrupt after this many steps (tests, benchmarks)
    WallClock checkpoint_clock = steady_wall_clock();  // the clock checkpoint intervals follow (tests: a fake one)
};

// Exit codes (documented in the README).
enum ExitCode : int {
    kExitOk = 0,
    kExitRuntimeError = 1,   // I/O failure, resume impossible, internal error
    kExitInputError = 2,     // bad scene file, mesh or command line
    kExitHealthFailure = 3,  // --strict and numerical trouble (lost shot, NaN, deep penetration)
    kExitInterrupted = 130,  // Ctrl-C / SIGTERM: checkpoint written, resume with --resume
};

int run_job(const RunOptions& options, std::ostream& out, std::ostream& err);

}  // namespace peensim
