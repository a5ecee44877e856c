// Peak memory of the process, for the run summary and the benchmark.
#pragma once

#include <cstdint>

namespace peensim {

// bytes, the peak resident set size of this process so far (getrusage ru_maxrss, which
// Linux reports in KiB); 0 if the kernel does not tell.
std::uint64_t peak_resident_bytes();

}  // namespace peensim
