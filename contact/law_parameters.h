// The parameters a contact law declares for the pairs it serves. One declaration feeds the scene
// schema (keys under `contacts.<pair>`, units, defaults, ranges, the `peensim schema` reference),
// the scene reader (which rejects a key the pair's law does not declare) and the law's factory.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
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

// The values of a law's parameters for one pair, SI, each under the name the law declares it with.
// A law reads them by name, not by position: reordering or inserting a declaration cannot hand a
// law another parameter's value.
struct ParameterValues {
    struct Named {
        std::string_view name;       // LawParameter::name (the declaration outlives the values)
        std::vector<double> values;  // SI; one value, or a table
    };
    std::vector<Named> parameters;

    bool has(std::string_view name) const { return find(name) != nullptr; }
    // Throws std::out_of_range naming the parameter when the pair has no value for it.
    const std::vector<double>& list(std::string_view name) const {
        if (const Named* p = find(name); p != nullptr && !p->values.empty()) return p->values;
        throw std::out_of_range("contact law parameter '" + std::string(name) + "' has no value");
    }
    double scalar(std::string_view name) const { return list(name).front(); }

private:
    const Named* find(std::string_view name) const {
        for (const Named& p : parameters)
            if (p.name == name) return &p;
        return nullptr;
    }
};

}  // namespace peensim::contact
