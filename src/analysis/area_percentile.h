// The value a share of a surface's area does not exceed, from per-triangle values and areas: the
// top of a map's colour scale. A plain maximum is set by a tiny triangle that took one impact (its
// rate per mm2 is huge) and leaves the rest of the map in the bottom colour.
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

namespace peensim {

// value_area: (value, area) per triangle, any order (sorted here); share: of the total area, 0..1.
// 0 for no triangles.
inline double area_percentile(std::vector<std::pair<double, double>> value_area, double share) {
    double total = 0.0;
    for (const auto& [value, area] : value_area) total += area;
    std::sort(value_area.begin(), value_area.end());
    double below = 0.0;
    for (const auto& [value, area] : value_area) {
        below += area;
        if (below >= share * total) return value;
    }
    return value_area.empty() ? 0.0 : value_area.back().first;
}

}  // namespace peensim
