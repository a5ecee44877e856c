#include "common/cycle_clock.h"

namespace peensim {

namespace {

double measure_seconds_per_cycle() {
#if defined(__x86_64__) || defined(__i386__)
    // Over 2 ms, the reads' own jitter (tens of ns) is ~1e-5 of the span.
    using clock = std::chrono::steady_clock;
    const auto t0 = clock::now();
    const std::uint64_t c0 = cycle_count();
    auto t1 = t0;
    while (t1 - t0 < std::chrono::milliseconds(2)) t1 = clock::now();
    const std::uint64_t c1 = cycle_count();
    const double seconds = std::chrono::duration<double>(t1 - t0).count();
    return c1 > c0 ? seconds / static_cast<double>(c1 - c0) : 1e-9;
#else
    return std::chrono::duration<double>(std::chrono::steady_clock::duration(1)).count();
#endif
}

}  // namespace

double seconds_per_cycle() {
    static const double value = measure_seconds_per_cycle();
    return value;
}

}  // namespace peensim
