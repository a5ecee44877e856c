// The replicas of a run other than its own (app/run/replica_plan.h), each on a thread: a
// Simulation of the shared, immutable model from its own shot placement, run to its window's end.
// The impacts of its window, moved to their place in the run, are spilled as raw records to a file
// in the run's directory and handed back in order once all are done (the run writes impacts.csv
// from them); its counts, speeds and lost shot come back for the summary.
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "app/run/replica_plan.h"
#include "engine/impact_record.h"
#include "engine/simulation_state.h"
#include "model/model.h"
#include "model/shot_placement.h"
#include "output/run_summary.h"
#include "output/speed_histogram.h"

namespace peensim {

struct ReplicaResult {
    ReplicaWindow window;
    RunSummary summary;  // its own, at its end: its counts include its warm-up's
    // Its summary's impact and slow-contact counts (same entries) when its window began: the
    // window's own are the difference.
    std::vector<std::uint64_t> impacts_at_window_start;
    std::vector<std::uint64_t> slow_contacts_at_window_start;
    std::vector<SpeedHistogram> speeds;  // its window's normal speeds, per logged component
    std::uint64_t logged_impacts = 0;    // its window's impacts on logged components
    std::vector<LostShot> lost;          // times in its own clock
    HealthCounters health;               // at its end (--strict counts every replica's)
    double wall_s = 0.0;                 // s
};

// The spills' folder in the run's directory (removed once read, and by a new run: run_directory.h).
inline constexpr std::string_view kReplicaSpillDirectory = "replicas";
// The slot of each component in the per-logged-component statistics (-1 if not logged).
std::vector<int> logged_slots(const Model& model);

// Replica r's spill, relative to the run's directory.
std::string replica_spill_name(int replica);

// The summary's impact and slow-contact counts of a state, in its entries' order (shot-shot, then
// each component).
std::vector<std::uint64_t> impact_counts(const SimulationState& state);
std::vector<std::uint64_t> slow_counts(const SimulationState& state);

// Hands a spill's impacts to `sink` in order, a batch at a time, then removes it.
void replay_spill(const std::string& path, const std::function<void(std::span<const ImpactRecord>)>& sink);

// Runs replica `window` of `model` from `shots` on this thread, from its own t = 0 to its window's
// end, spilling the window's impacts to replica_spill_name() in `run_dir`; stop() -> true ends it
// at its next step. slots: the logged slot of each component (-1: not logged).
ReplicaResult run_replica(std::shared_ptr<const Model> model, const ReplicaWindow& window, const InitialShots& shots,
                          const std::string& run_dir, const std::vector<int>& slots, const std::function<bool()>& stop);

// The other replicas of a run, wherever they run: threads of this process (ReplicaRuns) or the
// other ranks of an MPI job (app/run/replica_ranks.h). Their spills are in the run's directory.
class ReplicaRunner {
public:
    ReplicaRunner(std::vector<ReplicaWindow> windows, std::string run_dir);
    virtual ~ReplicaRunner() = default;
    ReplicaRunner(const ReplicaRunner&) = delete;
    ReplicaRunner& operator=(const ReplicaRunner&) = delete;

    // Asks every replica to stop at its next step (an interrupted run discards them).
    virtual void stop() = 0;
    // Waits for every replica; rethrows the first failure (after all have ended).
    virtual std::vector<ReplicaResult> wait() = 0;
    // Hands replica `k`'s (the k-th of the windows) spilled impacts to `sink` in order, a batch at a
    // time, then removes its spill. After wait().
    void replay(std::size_t k, const std::function<void(std::span<const ImpactRecord>)>& sink) const;
    // Removes the spills' folder (once all are read, or an interrupted or failed run).
    void discard() const;

protected:
    std::vector<ReplicaWindow> windows_;
    std::string dir_;
};

// The other replicas on threads of this process, sharing the immutable model.
class ReplicaRuns final : public ReplicaRunner {
public:
    // windows: the replicas to run (not replica 0); shots: each one's placement; slots: the logged
    // slot of each component (-1: not logged), as the run's speed histograms are kept.
    ReplicaRuns(std::shared_ptr<const Model> model, std::vector<ReplicaWindow> windows, std::vector<InitialShots> shots,
                std::string run_dir, std::vector<int> slots);
    ~ReplicaRuns() override;  // stops and joins whatever still runs

    void stop() override;
    std::vector<ReplicaResult> wait() override;

private:
    void run_one(std::size_t k);

    std::shared_ptr<const Model> model_;
    std::vector<InitialShots> shots_;
    std::vector<int> slots_;
    std::vector<ReplicaResult> results_;
    std::vector<std::exception_ptr> failures_;
    std::vector<std::thread> threads_;
    std::atomic<bool> stop_{false};
};

// Adds what another replica ran to the run's summary `s`: its health counters, stage times, steps
// and lost shot (all of its run, the warm-up too: the run's costs and its trouble).
void add_replica_work(RunSummary& s, const RunSummary& replica);

// Adds the replicas' windows to the run's summary `s` (replica 0's, with the merged speeds): their
// impacts and slow contacts within their windows, their steps, health counters and stage times,
// the state at the run's end (the last replica's), and the plan.
void merge_replica_summaries(RunSummary& s, const ReplicaPlan& plan, const std::vector<ReplicaResult>& results,
                             std::uint64_t own_logged_impacts);

}  // namespace peensim
