// The rounds over MPI ranks of a build without Open MPI (CMakeLists.txt compiles this file instead
// of round_ranks.cpp): never made, since run_replicas_over_mpi (replica_ranks_absent.cpp) refuses
// every run over ranks first.
#include <stdexcept>

#include "app/run/round_ranks.h"

namespace peensim {

RoundRanks::RoundRanks(const RoundPlan&, std::string run_dir) : RoundRunner(std::move(run_dir)) {
    throw std::logic_error("RoundRanks: a build without Open MPI");
}
RoundRanks::~RoundRanks() = default;
std::vector<SlotResult> RoundRanks::wait_round(int) { return {}; }
void RoundRanks::go(int) {}
void RoundRanks::stop() {}
std::vector<RoundReplicaResult> RoundRanks::finish() { return {}; }

int run_round_rank(const RoundRank&) { throw std::logic_error("run_round_rank: a build without Open MPI"); }

}  // namespace peensim
