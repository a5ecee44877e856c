// The parameters a contact law declares for the pairs it serves. One declaration feeds the scene
// schema (keys under `contacts.<pair>`, units, defaults, ranges, the `peensim schema` reference),
// the scene reader (which rejects a key the pair's law does not declare) and the law's factory.
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

#include "common/range.h"
#include "common/units.h"

namespace peensim::contact {

struct LawParameter {
    std::string_view name;           // key under contacts.<pair>
    Dimension dimension;             // of every value
    std::string_view default_value;  // as a scene would write it ("0.9", "0.5 m/s", "[0.4, 0.57]")
    Range range;                     // every value lies in it
    bool list = false;               // a table of values (at least one) instead of one value
    std::string_view doc;
};

// The values of a law's parameters for one pair, SI, in the order the law declares them.
struct ParameterValues {
    std::vector<std::vector<double>> values;

    double scalar(std::size_t i) const { return values.at(i).at(0); }
    const std::vector<double>& list(std::size_t i) const { return values.at(i); }
};

}  // namespace peensim::contact
