// `peensim run`: scene file -> model -> simulation, streaming impacts.csv, writing
// summary.json and the resolved scene, checkpointing for resume, reporting progress.
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "app/checkpoint/checkpoint_cadence.h"
#include "app/exit_codes.h"

namespace peensim {

// Where a run is, for a caller's progress display (the Python module's callback).
struct RunProgress {
    double time_s = 0.0;        // s, simulated time reached
    double duration_s = 0.0;    // s, the scene's process.duration
    std::uint64_t impacts = 0;  // impacts logged so far (a resumed run counts the earlier ones)
    double wall_s = 0.0;        // s, wall time of this run so far (a resumed run: its earlier sessions too)
};

struct RunOptions {
    std::string scene_path;
    // The scene as YAML text in memory (the Python module's dict): scene_path then only names it in
    // messages and is the directory relative mesh paths are read from. Empty: read scene_path.
    std::optional<std::string> scene_text;
    std::vector<std::string> overrides;  // --set path=value
    std::string output_dir;              // -o; "" = the scene's output.directory, else out/<scene name>
    bool progress = true;                // draw a progress bar (only on a terminal)
    bool resume = false;                 // continue from output_dir/checkpoint.bin
    bool strict = false;                 // fail (exit 3) if a serious health counter is non-zero
    bool analyze = true;                 // run `peensim analyze` on the outputs when the run finishes
    std::optional<bool> render;          // --render / --no-render; empty = as the scene's `render` block says
    // --replicas K: the run as K replicas of the chamber on K threads (app/run/replica_plan.h); 1: one
    // trajectory. A resumed run goes on as one replica.
    int replicas = 1;
    // The other replicas run on the other ranks of an MPI job (app/run/replica_ranks.h: it sets this
    // on rank 0), not on threads.
    bool replica_ranks = false;
    std::optional<std::uint64_t> stop_after_steps;     // interrupt after this many steps (tests, benchmarks)
    WallClock checkpoint_clock = steady_wall_clock();  // the clock checkpoint intervals follow (tests: a fake one)
    // Asked after every step whether to stop (checkpoint, exit 130). Empty: Ctrl-C and SIGTERM, caught
    // by the run (interrupt.h). A caller that owns the signals (Python) passes its own test.
    std::function<bool()> stop_requested;
    // Called about every kProgressCallbackInterval_s of wall time and once at the end (finished or
    // stopped), on the run's thread.
    std::function<void(const RunProgress&)> on_progress;
    // A folder of coverage geometries to reuse and keep (app/analysis/coverage_geometry_cache.h):
    // the runs of a sweep share one. "": computed by the run, kept nowhere.
    std::string geometry_cache_dir;
};

inline constexpr double kProgressCallbackInterval_s = 0.25;  // s of wall time between on_progress calls

int run_job(const RunOptions& options, std::ostream& out, std::ostream& err);

struct SceneDescription;
// Where a run of `scene` writes: -o, else the scene's output.directory, else out/<scene file's stem>.
std::string run_output_directory(const RunOptions& options, const SceneDescription& scene);

// The same, with bad input thrown (InputError: file, line, field) instead of reported; the other
// outcomes are its exit codes (0, 3 for --strict, 130 stopped). For a caller with exceptions of its own.
int run_scene(const RunOptions& options, std::ostream& out, std::ostream& err);

}  // namespace peensim
