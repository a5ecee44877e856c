// `peensim sweep`: the variants of a scene (sweep_plan.h) run as ordinary runs, several at once on
// the local cores, each in its own directory with the outputs `run` gives it; then compared
// (sweep_compare.h). Each run is the `peensim run` process itself, so a variant's results are
// those of running it alone. Resumable: a finished run is never rerun, an interrupted one resumes
// from its checkpoint; a failed run is retried once, then reported, and the sweep goes on.
#pragma once

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace peensim {

struct SweepOptions {
    std::string scene_path;              // a scene file, or a sweep file (sweep_file.h) that names one
    std::string output_dir;              // -o: the sweep's directory
    std::vector<std::string> vary;       // --vary path=v1,v2,...
    std::vector<std::string> overrides;  // --set, every run
    std::optional<long long> seeds;      // --seeds: replicates per variant (process.seed, seed + 1, ...); none: the sweep file's, else 1
    int jobs = 0;                        // --jobs: runs at once (0: every core)
    std::string baseline;                // --baseline: the variant the others are compared with ("" = the first)
    std::string executable;              // the peensim binary the runs are ("" = this process's own)
    // Asked every few ms whether to stop (the runs checkpoint, exit 130). Empty: Ctrl-C and SIGTERM,
    // caught by the sweep (interrupt.h). A caller that owns the signals (Python) passes its own test.
    std::function<bool()> stop_requested;
};

// Exit codes as `run`'s: 0 all runs finished, 2 a bad command line or scene, 1 a run failed for good (twice, or once refusing its input)
// (the others finished and were compared), 130 interrupted (the runs checkpointed; run the same
// command again to go on).
int sweep_job(const SweepOptions& options, std::ostream& out, std::ostream& err);

// The same, with bad input thrown (InputError: file, line, field) instead of reported.
int run_sweep(const SweepOptions& options, std::ostream& out, std::ostream& err);

}  // namespace peensim
