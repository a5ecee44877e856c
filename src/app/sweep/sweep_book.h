// The bookkeeping of a sweep's runs, whoever runs them (child processes of this process, or MPI
// ranks): which are still to run, each one's attempts (a failed run goes back into the queue
// once), what finished and what failed, and the progress lines. And how one run is started: the
// `peensim run` process itself, in a process group of its own, dying with its parent.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <deque>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "app/sweep/sweep_plan.h"

namespace peensim {

class SweepBook {
public:
    // Queues every run of `plan` that has not finished yet (summary and analysis written); `slots`:
    // how many run at once (for the time still to go); `job`: the lines' prefix ("sweep",
    // "optimise"), `job_noun` what goes on without a failed run ("sweep", "optimisation").
    SweepBook(const SweepPlan& plan, std::string logs_dir, int slots, std::ostream& out, std::ostream& err, std::string job = "sweep",
              std::string job_noun = "sweep");

    bool has_queued() const { return !queue_.empty(); }
    std::size_t take();                            // the next run to start: one more attempt of it
    void outcome(std::size_t run, int exit_code);  // a run ended with this exit code
    void stop();                                   // interrupted: nothing more is handed out
    bool stopped() const { return stopped_; }

    std::size_t done() const { return done_; }
    std::size_t total() const { return plan_.runs.size(); }
    const std::vector<std::size_t>& failed() const { return failed_; }
    std::string log_of(std::size_t run) const;    // the run's messages: logs_dir/<variant>.s<k>.log
    std::string label_of(std::size_t run) const;  // "<variant>/s<k>"

private:
    void failed_for_good(std::size_t run);  // not run again; its folders removed if it left them empty

    const SweepPlan& plan_;
    std::string logs_;
    int slots_;
    std::ostream& out_;
    std::ostream& err_;
    std::string job_, job_noun_;
    std::deque<std::size_t> queue_;
    std::map<std::size_t, int> attempts_;
    std::vector<std::size_t> failed_;
    std::size_t done_ = 0, done_here_ = 0;
    bool stopped_ = false;
    std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
};

// Starts `executable run scene -o <run dir> --quiet --threads N --geometry-cache C [--resume] --set
// ...` (resuming from the run's checkpoint if it has one; N: the cores its analysis uses, its share
// of those the sweep runs on; C: sweep_geometry_cache of the logs' folder, which the runs of one
// sweep share), stdin from /dev/null, stdout and stderr appended to `log`, in a process group of
// its own. It dies with the thread that started it (SIGKILL, PR_SET_PDEATHSIG): a sweep or MPI rank
// killed outright leaves no run behind holding its directory.
pid_t start_sweep_run(const std::string& executable, const std::string& scene, const SweepRun& run, const std::string& log,
                      unsigned threads);

// The folder a sweep's runs keep the parts' coverage geometry in for each other
// (app/analysis/coverage_geometry_cache.h): geometry-cache/ beside logs_dir.
std::string sweep_geometry_cache(const std::string& logs_dir);

// How often the runs whose messages are in logs_dir computed a part's coverage geometry and how
// often they reused it from the cache (their "note: <part>'s coverage geometry ..." lines), as a
// line for the end of a sweep or an optimisation: "geometry: the runs computed ... (<cache>)\n",
// or "" when no run used the cache.
std::string sweep_geometry_cache_line(const std::string& logs_dir);

// Where run `run`'s messages go: logs_dir/<variant>.s<k>.log.
std::string sweep_run_log(const SweepPlan& plan, const std::string& logs_dir, std::size_t run);

// The exit code of a waited-for process (128 + the signal that ended it).
int exit_code_of(int wait_status);

}  // namespace peensim
