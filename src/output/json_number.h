// A double as a JSON value: the number, or null where it is not finite (JSON has no NaN or
// infinity; a figure that does not exist is written as null).
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>

namespace peensim {

inline nlohmann::ordered_json json_number(double x) {
    return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr);
}

}  // namespace peensim
