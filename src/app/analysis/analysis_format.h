// Numbers in the analysis tables and report: significant digits, and an empty cell for a value
// that does not exist (NaN: a mean without impacts), never "nan".
#pragma once

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

namespace peensim {

inline std::string fmt(double v, int precision = 4) {
    if (!std::isfinite(v)) return "";
    std::ostringstream s;
    s << std::setprecision(precision) << v;
    return s.str();
}

}  // namespace peensim
