// Runs the runs of a sweep plan that have not finished: as child processes on the local cores, or,
// on rank 0 of an MPI job, handed out over the ranks (sweep_mpi.h). What a sweep and an
// optimisation (app/optimise/) share: both plan runs, then run them here.
#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "app/interrupt.h"
#include "app/sweep/sweep_plan.h"

namespace peensim {

class MpiSweep;

struct SweepRunner {
    std::string executable;          // the peensim binary each run is
    std::string scene_path;          // the scene every run reads (with its --set)
    std::string logs_dir;            // each run's messages: <logs_dir>/<variant>.s<k>.log
    int jobs = 1;                    // runs at once here (an MPI rank: per rank)
    MpiSweep* mpi = nullptr;         // rank 0 of an MPI job: the other ranks run too (nullptr: local only)
    std::string job = "sweep";       // the progress lines' prefix ("optimise")
    std::string job_noun = "sweep";  // what goes on without a failed run ("optimisation")
};

struct SweepOutcome {
    bool stopped = false;  // interrupted: the running runs checkpointed, nothing new started
    std::size_t done = 0, total = 0;
    std::vector<std::size_t> failed;  // runs that failed for good: twice, or once refusing their input (indices into plan.runs)
};

// Runs every unfinished run of `plan` (a finished run, summary and analysis written, is never
// rerun; an interrupted one resumes from its checkpoint; a failed one is retried once, unless it
// refused its input: exit 2). Prints
// `headline` (what is about to run: "sweep: 3 variants x 2 seeds") with " = N runs, J at once"
// (or " over K MPI ranks") and how many finished before, then the progress lines.
SweepOutcome run_sweep_plan(const SweepPlan& plan, const SweepRunner& runner, const StopRequest& stop, const std::string& headline,
                            std::ostream& out, std::ostream& err);

// This process's own binary (/proc/self/exe), the runs' default.
std::string this_executable();

}  // namespace peensim
