// What a test sets before it starts `mpirun`: leave to run as root (this machine's CI), and under
// the sanitizers (the asan preset) keep Open MPI's plugins loaded and whole stacks, so that its own
// allocations left at exit are told apart from ours by the suppressions
// (tests/lsan-suppressions.txt). Whole stacks (fast_unwind_on_malloc=0) reach the `peensim run`
// children of an MPI sweep too, through the environment, and there they deadlock llvmpipe: its JIT
// allocates while it holds libgcc's unwinder lock (RuntimeDyldELF::registerEHFrames), and the
// sanitizer's slow unwind of that allocation takes the same lock. So under the sanitizers these
// children draw with softpipe, Mesa's rasterizer without a JIT (the tests compare logs, not pixels).
#pragma once

#include <cstdlib>
#include <string>

namespace peensim::testing {

inline void mpirun_environment() {
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
#if defined(__SANITIZE_ADDRESS__)
    ::setenv("OMPI_MCA_mca_base_component_disable_dlclose", "1", 1);
    if (const char* asan = std::getenv("ASAN_OPTIONS");
        asan == nullptr || std::string(asan).find("fast_unwind_on_malloc") == std::string::npos)
        ::setenv("ASAN_OPTIONS", (std::string(asan != nullptr ? asan : "") + ":fast_unwind_on_malloc=0").c_str(), 1);
    ::setenv("GALLIUM_DRIVER", "softpipe", 1);
#endif
}

}  // namespace peensim::testing
