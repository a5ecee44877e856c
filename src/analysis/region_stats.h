// Impact statistics of one region: the per-triangle fields summed or weighted over its triangles.
#pragma once

#include <cstdint>

#include "analysis/coverage_map.h"
#include "analysis/regions.h"
#include "analysis/triangle_fields.h"

namespace peensim {

struct RegionStats {
    std::size_t triangles = 0;
    double area_m2 = 0.0;  // m2
    std::uint64_t impacts = 0;
    double impacts_per_mm2_s = 0.0;  // 1/(mm2 s), impacts / area / duration (NaN for zero area)
    double mean_normal_speed = 0.0;  // m/s, over the region's impacts (NaN without impacts)
    double max_normal_speed = 0.0;   // m/s (0 without impacts)
    double energy_per_area = 0.0;    // J/m2, 1/2 m vn^2 delivered / area (NaN for zero area)
    double coverage = 0.0;           // 0..1, area-weighted (NaN without a coverage map)
};

// coverage: the component's coverage map, or nullptr (no yield stress); duration_s: simulated s.
RegionStats region_stats(const Region& region, const TriangleFields& fields, const CoverageMap* coverage, double duration_s);

}  // namespace peensim
