#include "analysis/region_stats.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace peensim {

RegionStats region_stats(const Region& region, const TriangleFields& fields, const CoverageMap* coverage, double duration_s) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    RegionStats s;
    s.triangles = region.triangles.size();
    double speed_sum = 0.0;  // m/s, summed over impacts
    double energy = 0.0;     // J
    for (int i : region.triangles) {
        const auto t = static_cast<std::size_t>(i);
        const double area = fields.area_m2(t);
        s.area_m2 += area;
        s.impacts += fields.count(t);
        if (fields.count(t) > 0) speed_sum += fields.mean_normal_speed(t) * static_cast<double>(fields.count(t));
        s.max_normal_speed = std::max(s.max_normal_speed, fields.max_normal_speed(t));
        if (area > 0.0) energy += fields.energy_per_area(t) * area;
    }
    const bool has_area = s.area_m2 > 0.0;
    s.impacts_per_mm2_s = has_area ? static_cast<double>(s.impacts) / (s.area_m2 * 1e6) / duration_s : nan;
    s.mean_normal_speed = s.impacts > 0 ? speed_sum / static_cast<double>(s.impacts) : nan;
    s.energy_per_area = has_area ? energy / s.area_m2 : nan;
    s.coverage = coverage != nullptr ? coverage->coverage_of(region.triangles) : nan;
    return s;
}

}  // namespace peensim
