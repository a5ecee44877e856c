// Whether an MPI launcher started this process: from the launcher's environment alone, so that a
// build without MPI (sweep_mpi_absent.cpp) can tell too.
#include <cstdlib>

#include "app/mpi_launch.h"

namespace peensim {

bool launched_by_mpi() {
    for (const char* size : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"})
        if (const char* v = std::getenv(size); v != nullptr && std::atoi(v) > 1) return true;
    return false;
}

}  // namespace peensim
