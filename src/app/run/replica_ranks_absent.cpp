// The replicas over MPI ranks of a build without Open MPI (CMakeLists.txt compiles this file
// instead of replica_ranks.cpp when MPI is not installed): under mpirun, a run with --replicas says
// what is missing instead of running every rank's copy of the whole run into one directory.
#include <ostream>
#include <stdexcept>

#include "app/exit_codes.h"
#include "app/run/replica_ranks.h"

namespace peensim {

int run_replicas_over_mpi(const RunOptions& options, std::ostream&, std::ostream& err) {
    err << "error: this peensim was built without Open MPI, so --replicas " << options.replicas
        << " cannot spread over MPI ranks: apt-get install libopenmpi-dev openmpi-bin, configure and build again (or run without "
           "mpirun: the replicas then run on this machine's cores)\n";
    return kExitInputError;
}

// Never made in this build (run_replicas_over_mpi is the only way in).
ReplicaRanks::ReplicaRanks(std::vector<ReplicaWindow> windows, std::string run_dir)
    : ReplicaRunner(std::move(windows), std::move(run_dir)) {
    throw std::logic_error("ReplicaRanks: a build without Open MPI");
}
ReplicaRanks::~ReplicaRanks() = default;
void ReplicaRanks::stop() {}
std::vector<ReplicaResult> ReplicaRanks::wait() { return {}; }

void release_replica_ranks() {}

}  // namespace peensim
