// A run's replicas over the ranks of an MPI job: `mpirun -n K peensim run SCENE --replicas K`.
// Rank 0 is the run itself (replica 0: the pilot, the plan, the outputs, the analysis); rank k
// reads the same scene, places replica k's load from its own seed, waits for the plan, runs its
// window, spills its impacts into the run's directory (a file system every rank sees, as a
// cluster's shared scratch) and hands its result to rank 0 by message. The same seed and K give
// the bytes of `--replicas K` on threads: the replicas are the same, only where they run differs.
// Messages are polled with short sleeps, so a rank that waits leaves its core to the others (an
// oversubscribed job on a few cores still runs at their speed).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "app/run/replica_runs.h"
#include "app/run/run_job.h"

namespace peensim {

// A run as replicas over MPI ranks, from any rank: rank 0 runs the run (out, err its streams),
// the others their replicas, quietly. --replicas must equal the ranks (exit 2 otherwise).
int run_replicas_over_mpi(const RunOptions& options, std::ostream& out, std::ostream& err);

// Rank 0's side of the other replicas: constructing it hands the windows to their ranks (window k
// to rank k + 1); wait() collects their results.
class ReplicaRanks final : public ReplicaRunner {
public:
    ReplicaRanks(std::vector<ReplicaWindow> windows, std::string run_dir);
    ~ReplicaRanks() override;  // collects whatever is still owed (so that every message is matched)
    void stop() override;      // tells every rank to stop at its next step
    std::vector<ReplicaResult> wait() override;

private:
    bool stopped_ = false;
    bool collected_ = false;
};

// Rank 0 when the run will have no other replicas (it goes on as one, was resumed, or failed):
// tells the other ranks, which then end. Once per job; later calls, or after a plan, do nothing.
void release_replica_ranks();

}  // namespace peensim
