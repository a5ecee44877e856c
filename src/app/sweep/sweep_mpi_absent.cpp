// The MPI sweep of a build without Open MPI (CMakeLists.txt compiles this file instead of
// sweep_mpi.cpp when MPI is not installed): launched under mpirun, a sweep says what is missing
// instead of running every rank's copy of the whole sweep.
#include <stdexcept>

#include "app/sweep/sweep_mpi.h"

namespace peensim {

MpiSweep::MpiSweep() {
    throw std::runtime_error(
        "this peensim was built without Open MPI, so a sweep cannot spread over MPI ranks: apt-get install libopenmpi-dev openmpi-bin, "
        "configure and build again (or run the sweep without mpirun: it uses the local cores)");
}

MpiSweep::~MpiSweep() = default;

// Never reached: no MpiSweep is ever made in this build.

void MpiSweep::coordinate(SweepBook&, const std::string&, const std::string&, const SweepPlan&, int, const StopRequest&) {}

std::string MpiSweep::broadcast(const std::string& text) const { return text; }

void MpiSweep::work(const std::string&, const std::string&, const SweepPlan&, const std::string&, const StopRequest&) {}

}  // namespace peensim
