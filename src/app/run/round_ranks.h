// A run until coverage over the ranks of an MPI job: `mpirun -n K peensim run SCENE --replicas K
// --until-coverage 98%`. The rounds of app/run/replica_rounds.h, with replica k on rank k instead
// of a thread: rank 0 is the run (replica 0, its pilot and plan, the log, the coverage watch, every
// output); rank k runs its slots as a thread would (round_runs.h: run_round_replica), spills each
// into the run's directory (every rank must see it) and tells rank 0 by message, then waits for
// rank 0's word to run the next round or to stop. The same seed and K give the bytes of the same
// run on threads: the replicas and the log are the same, only where a replica runs differs.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/run/round_runs.h"

namespace peensim {

// Rank 0's side of the other replicas' rounds: constructing it makes the spills' folder and hands
// the plan to every other rank (replica k on rank k), which starts round 0 at once.
class RoundRanks final : public RoundRunner {
public:
    RoundRanks(const RoundPlan& plan, std::string run_dir);
    ~RoundRanks() override;  // stops and collects whatever is still owed (so that every message is matched)

    std::vector<SlotResult> wait_round(int round) override;
    void go(int round) override;
    void stop() override;
    std::vector<RoundReplicaResult> finish() override;

private:
    struct Rank {
        std::vector<SlotResult> slots;             // its whole slots, round by round
        bool ended = false;                        // its result (or failure) is in: no more slots
        std::optional<RoundReplicaResult> result;  // when it ended well
        std::string failure;                       // when it did not
    };
    // Takes the next message of other replica k (rank k + 1) if one is waiting; false if none.
    bool take_message(std::size_t k);
    void wait_until(std::size_t k, const std::function<bool(const Rank&)>& done);

    std::vector<Rank> ranks_;
    bool stopped_ = false;
    bool finished_ = false;
};

// What rank k (>= 1) of a run until coverage brings to its rounds: the scene's model and its
// replica's shot placement, the run's directory and logged slots (as rank 0 computes them), why
// it cannot run if it cannot (empty: it can), and the plan's bytes as rank 0 sent them.
struct RoundRank {
    std::shared_ptr<const Model> model;
    InitialShots shots;
    std::string run_dir;
    std::vector<int> slots;
    std::string failure;
    std::string plan_bytes;
    int rank = 1;
};

// Rank k's rounds, quietly: its slots as rank 0 lets them run, each reported when spilled; then its
// result (or why it failed) to rank 0, and it ends on rank 0's word. It stops only when rank 0 says
// so, not on a Ctrl-C of its own (the launcher's reaches rank 0 too): a replica that stopped by
// itself would end the log early, as one that reached the run's duration does.
int run_round_rank(const RoundRank& rank);

}  // namespace peensim
