// The shipped scenes the tests run, by their path in the source tree.
#pragma once

#include <string>

namespace peensim::testing {

inline const std::string kRod = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml";

}  // namespace peensim::testing
