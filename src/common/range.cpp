#include "common/range.h"

#include "common/units.h"

namespace peensim {

bool Range::contains(double v) const {
    if (lo_open ? !(v > lo) : !(v >= lo)) return false;
    if (hi_open ? !(v < hi) : !(v <= hi)) return false;
    return true;
}

std::string number_text(double v) {
    if (v == std::numeric_limits<double>::infinity()) return "inf";
    if (v == -std::numeric_limits<double>::infinity()) return "-inf";
    return format_si(v);
}

std::string Range::text() const {
    const bool has_lo = lo != -std::numeric_limits<double>::infinity();
    const bool has_hi = hi != std::numeric_limits<double>::infinity();
    if (has_lo && has_hi) return std::string(lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) + (hi_open ? ")" : "]");
    if (has_lo) return std::string(lo_open ? "> " : ">= ") + number_text(lo);
    if (has_hi) return std::string(hi_open ? "< " : "<= ") + number_text(hi);
    return "";
}

}  // namespace peensim
