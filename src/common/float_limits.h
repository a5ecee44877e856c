// The special doubles the code compares against or stores for "none": one definition for every
// file (each file defining its own clashes when the build joins files into one unit).
#pragma once

#include <limits>

namespace peensim {

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kEps = std::numeric_limits<double>::epsilon();  // the gap between 1 and the next double

}  // namespace peensim
