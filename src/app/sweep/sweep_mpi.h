// A sweep over the ranks of an MPI job (`mpirun -n K peensim sweep ...`, under Slurm `srun`): rank 0
// hands the runs out one at a time as ranks free up (long and short runs balance), collects how
// each ended, and compares them; every rank, rank 0 included, runs its runs as `peensim run` child
// processes, one at a time (MPI places one rank per core; --jobs gives a rank more). The runs'
// results do not depend on where they ran: each is the same process with the same arguments.
#pragma once

#include <string>

#include "app/interrupt.h"
#include "app/mpi_launch.h"
#include "app/sweep/sweep_book.h"
#include "app/sweep/sweep_plan.h"

namespace peensim {

// MPI_Init on construction, MPI_Finalize on destruction.
class MpiSweep {
public:
    MpiSweep();
    ~MpiSweep();
    MpiSweep(const MpiSweep&) = delete;
    MpiSweep& operator=(const MpiSweep&) = delete;
    int rank() const { return rank_; }
    int size() const { return size_; }

    // Rank 0: hands out `book`'s runs to the other ranks and runs `slots` at once itself, until
    // every run has ended (or, interrupted, every running one has checkpointed).
    void coordinate(SweepBook& book, const std::string& executable, const std::string& scene, const SweepPlan& plan, int slots,
                    const StopRequest& stop);
    // The other ranks: ask rank 0 for a run, run it, report its exit code, until told to stop.
    void work(const std::string& executable, const std::string& scene, const SweepPlan& plan, const std::string& logs_dir,
              const StopRequest& stop);

    // Rank 0's `text` on every rank (the others pass anything): how rank 0 tells the ranks what
    // to run next when it plans as it goes (an optimisation's rounds).
    std::string broadcast(const std::string& text) const;

private:
    int rank_ = 0, size_ = 1;
};

}  // namespace peensim
