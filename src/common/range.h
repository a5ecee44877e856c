// Allowed values of a number: the scene schema's ranges and the parameters a contact law declares.
#pragma once

#include <limits>
#include <string>

namespace peensim {

// Allowed values of a quantity or integer (SI). Open ends are excluded, closed ends included.
struct Range {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool lo_open = false;
    bool hi_open = false;

    bool unbounded() const { return lo == -std::numeric_limits<double>::infinity() && hi == std::numeric_limits<double>::infinity(); }
    bool contains(double v) const;
    std::string text() const;  // "> 0", ">= 0", "(0, 1]", "[0, 1]", "" if unbounded
};

constexpr Range above(double lo) { return Range{lo, std::numeric_limits<double>::infinity(), true, false}; }
constexpr Range at_least(double lo) { return Range{lo, std::numeric_limits<double>::infinity(), false, false}; }
constexpr Range open_closed(double lo, double hi) { return Range{lo, hi, true, false}; }
constexpr Range closed(double lo, double hi) { return Range{lo, hi, false, false}; }
constexpr Range open_open(double lo, double hi) { return Range{lo, hi, true, true}; }

// A bound as text: SI number, "inf" or "-inf".
std::string number_text(double v);

}  // namespace peensim
