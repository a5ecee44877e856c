// `peensim optimise STUDY.yaml -o DIR`: searches the study's process variables (study_file.h) for
// the setting that minimises (or maximises) its objective under its constraints, by Bayesian
// optimisation (bayes_search.h) over ordinary runs: each round's settings run as a sweep's runs
// (locally, or over the ranks of an MPI job), a first space-filling design, then rounds of the
// settings of highest expected improvement, with more seeds where the winner's interval is wider
// than the study's tolerance. Ends with independent runs of the winner and of the start (fresh
// seeds) and a report (optimise_report.h). Resumable: the same command skips every finished run
// and goes on from the journal.
#pragma once

#include <functional>
#include <optional>
#include <ostream>
#include <string>

namespace peensim {

struct OptimiseOptions {
    std::string study_path;
    std::string output_dir;
    int jobs = 0;                          // runs at once (0: every core; under MPI: per rank, 1)
    std::optional<int> runs;               // --runs: the search's budget, instead of the study's
    std::string executable;                // the peensim binary the runs are ("" = this process's own)
    std::function<bool()> stop_requested;  // as SweepOptions'
};

// Exit codes as a sweep's: 0 done, 2 bad input, 1 a run failed for good (the search went on without
// it), 130 interrupted (run the same command to go on).
int optimise_job(const OptimiseOptions& options, std::ostream& out, std::ostream& err);
int run_optimise(const OptimiseOptions& options, std::ostream& out, std::ostream& err);  // InputError thrown

}  // namespace peensim
