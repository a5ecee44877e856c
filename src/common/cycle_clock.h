// A clock for timing short stretches of the hot loops (the step stages' timers): the processor's
// time-stamp counter where there is one. Reading steady_clock around each prediction of the event
// scheme cost 3-4 % of a dense or soft run (perf: __vdso_clock_gettime); the counter is read in a
// few cycles. Its rate is measured once per process against steady_clock.
#pragma once

#include <chrono>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

namespace peensim {

// Ticks of the counter (or nanoseconds of steady_clock where there is none).
inline std::uint64_t cycle_count() {
#if defined(__x86_64__) || defined(__i386__)
    return __rdtsc();
#else
    return static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
#endif
}

// s per tick of cycle_count(), measured on first use (about 2 ms).
double seconds_per_cycle();

}  // namespace peensim
