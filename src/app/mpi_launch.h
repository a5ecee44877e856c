// Whether an MPI launcher started this process (app/sweep/sweep_mpi.h: a sweep over the ranks;
// app/run/replica_ranks.h: a run's replicas over the ranks).
#pragma once

namespace peensim {

// More than one rank, from the launcher's environment alone (Open MPI's, PMI's or PMIx's), so that
// a build without MPI can tell too.
bool launched_by_mpi();

}  // namespace peensim
