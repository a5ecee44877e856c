// The few aligned lines printed at the end of a run (or when it is interrupted): how far it
// got, how fast, impacts and their normal speeds per component, health counters, memory.
#pragma once

#include <string>

#include "output/run_summary.h"

namespace peensim {

// Lines end with '\n'. Only non-zero health counters are listed ("all zero" otherwise).
std::string summary_to_text(const RunSummary& summary);

}  // namespace peensim
