// The other replicas of a run until coverage (app/run/replica_rounds.h): each a Simulation of the
// scene from its own shot placement, run slot by slot, on a thread (RoundRuns) or an MPI rank
// (app/run/round_ranks.h). Each slot's impacts, moved to their place in the run, are spilled to a
// file of their own in the run's directory; after each slot the replica waits until the run lets
// it go on (the run has logged the round and not yet reached its target) or stops it.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "app/run/replica_rounds.h"
#include "engine/impact_record.h"
#include "engine/simulation_state.h"
#include "model/model.h"
#include "model/shot_placement.h"
#include "output/run_summary.h"

namespace peensim {

// One replica's slot of one round, as it ran.
struct SlotResult {
    ReplicaWindow window;  // its own time [log_from_s, run_to_s) (its end at the run's duration, if that comes first)
    std::string spill;     // its impacts' file
    std::uint64_t logged_impacts = 0;
    // The summary's impact and slow-contact counts (impact_counts(), slow_counts()) at its start
    // and end: the slot's own are the difference.
    std::vector<std::uint64_t> impacts_at_start, slow_contacts_at_start;
    std::vector<std::uint64_t> impacts_at_end, slow_contacts_at_end;
};

// One replica's whole run, once it has stopped.
struct RoundReplicaResult {
    int replica = 0;
    std::uint64_t seed = 0;
    double first_from_s = 0.0;   // s, its own time its first slot began
    RunSummary summary;          // its own, at its end (steps, stage times, health: everything it ran)
    std::vector<LostShot> lost;  // times in its own clock
    HealthCounters health;
};

// Replica k's (>= 1) whole run until coverage on this thread: a Simulation of `model` from `shots`,
// slot by slot. Before round r it asks may_run(r) (false: it stops); each whole slot goes to
// `publish`; stop() -> true ends it at its next step (the slot it is in is then not published).
// Its spills go to `run_dir`; slots: the logged slot of each component (-1: not logged).
RoundReplicaResult run_round_replica(std::shared_ptr<const Model> model, const RoundPlan& plan, int replica, const InitialShots& shots,
                                     const std::string& run_dir, const std::vector<int>& slots, const std::function<bool(int)>& may_run,
                                     const std::function<void(SlotResult)>& publish, const std::function<bool()>& stop);

// The other replicas of a run until coverage, wherever they run: threads of this process
// (RoundRuns) or the other ranks of an MPI job (app/run/round_ranks.h). Their spills are in the
// run's directory.
class RoundRunner {
public:
    virtual ~RoundRunner() = default;
    // Waits until every other replica has ended its slot of `round` (or stopped); their slots of
    // that round in replica order, up to the first that has none (a replica that reached the
    // run's duration). Rethrows the first failure.
    virtual std::vector<SlotResult> wait_round(int round) = 0;
    // Lets them run round `round`.
    virtual void go(int round) = 0;
    // Asks every replica to stop at its next step, or not to start another slot.
    virtual void stop() = 0;
    // Stops them and waits for their ends; each one's result. Rethrows the first failure.
    virtual std::vector<RoundReplicaResult> finish() = 0;
    // Removes the spills' folder.
    void discard() const;

protected:
    explicit RoundRunner(std::string run_dir) : dir_(std::move(run_dir)) {}
    std::string dir_;
};

// The other replicas on threads of this process, sharing the immutable model.
class RoundRuns final : public RoundRunner {
public:
    // shots: the placement of replicas 1..K-1; slots: the logged slot of each component (-1: not
    // logged). They start round 0 at once.
    RoundRuns(std::shared_ptr<const Model> model, RoundPlan plan, std::vector<InitialShots> shots, std::string run_dir,
              std::vector<int> slots);
    ~RoundRuns() override;  // stops and joins whatever still runs
    RoundRuns(const RoundRuns&) = delete;
    RoundRuns& operator=(const RoundRuns&) = delete;

    std::vector<SlotResult> wait_round(int round) override;
    void go(int round) override;
    void stop() override;
    std::vector<RoundReplicaResult> finish() override;

private:
    struct Worker;
    void run_one(std::size_t i);
    bool may_run(int round);  // blocks until the round may run (true) or the replicas stop (false)
    void publish(std::size_t i, std::optional<SlotResult> slot, bool ended);

    std::shared_ptr<const Model> model_;
    RoundPlan plan_;
    std::vector<InitialShots> shots_;
    std::vector<int> slots_;
    std::mutex mutex_;
    std::condition_variable changed_;
    int allowed_round_ = 0;  // guarded by mutex_
    std::atomic<bool> stop_{false};
    std::vector<std::unique_ptr<Worker>> workers_;
    std::vector<std::thread> threads_;
};

// Adds the other replicas' impacts and slow contacts in their logged slots to the summary's
// entries (in impact_counts() order: shot-shot, then each component). Empty: none.
void add_slot_counts(RunSummary& s, const std::vector<std::uint64_t>& impacts, const std::vector<std::uint64_t>& slow_contacts);

// The rounds into the run's summary (replica 0's, with the log's speeds and the slots' counts): the
// plan and the slots logged, and what the other replicas ran (steps, stage times, health, lost shot).
void merge_round_summaries(RunSummary& s, const RoundPlan& plan, std::vector<RunSummary::Replicas::Window> slots,
                           const std::vector<RoundReplicaResult>& results);

}  // namespace peensim
