#include "analysis/region_stats.h"

#include <cmath>
#include <limits>

namespace peensim {

RegionStats region_stats(const RegionSet& regions, std::size_t r, const RegionTally& tally, const CoverageProgress* coverage,
                         double duration_s) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    RegionStats s;
    s.triangles = regions.shares(r).size();
    s.area_m2 = regions.area_m2(r);
    s.peened_area_m2 = coverage != nullptr ? coverage->classes().region_peened_area_m2(r) : nan;
    s.unreachable_area_m2 = coverage != nullptr ? coverage->classes().region_unreachable_area_m2(r) : nan;
    s.impacts = tally.impacts;
    const bool has_area = s.area_m2 > 0.0;
    s.impacts_per_mm2_s = has_area ? static_cast<double>(s.impacts) / (s.area_m2 * 1e6) / duration_s : nan;
    s.mean_normal_speed = s.impacts > 0 ? tally.speed_sum / static_cast<double>(s.impacts) : nan;
    s.max_normal_speed = tally.max_speed;
    s.energy_per_area = has_area ? tally.energy_J / s.area_m2 : nan;
    s.coverage = coverage != nullptr ? coverage->region_coverage(r) : nan;
    return s;
}

}  // namespace peensim
