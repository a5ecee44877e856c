// Numbers in the analysis tables and report: significant digits, and an empty cell for a value
// that does not exist (NaN: a mean without impacts), never "nan".
#pragma once

#include <charconv>
#include <cmath>
#include <string>

namespace peensim {

// printf's %.<precision>g, which is what a stream with that precision wrote (std::to_chars is
// specified so), without a stream per number: a 500k-triangle part's tables hold millions of them.
// A zero is "0" whatever its sign: "-0" (a change of -0.0, a negated zero bound) tells a reader nothing.
inline std::string fmt(double v, int precision = 4) {
    if (!std::isfinite(v)) return "";
    if (v == 0.0) v = 0.0;
    char text[64];
    const std::to_chars_result r = std::to_chars(text, text + sizeof text, v, std::chars_format::general, precision);
    return std::string(text, r.ptr);
}

}  // namespace peensim
