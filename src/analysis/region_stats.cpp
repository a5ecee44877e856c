#include "analysis/region_stats.h"

#include <cmath>
#include <limits>

namespace peensim {

namespace {

// A region's weight of triangle t's area in its coverage (see region_coverage).
double coverage_weight(const RegionSet& regions, std::size_t r, const RegionShare& s, std::span<const double> peened) {
    return regions.excluded(r) ? s.fraction : s.fraction * peened[static_cast<std::size_t>(s.triangle)];
}

}  // namespace

double region_coverage(const RegionSet& regions, std::size_t r, const CoverageMap& coverage, std::span<const double> peened) {
    double covered = 0.0, area = 0.0;  // m2
    for (const RegionShare& s : regions.shares(r)) {
        const auto t = static_cast<std::size_t>(s.triangle);
        const double a = coverage_weight(regions, r, s, peened) * coverage.triangle_area(t);
        area += a;
        covered += a * coverage.coverage_of_triangle(t);
    }
    return area > 0.0 ? covered / area : std::numeric_limits<double>::quiet_NaN();
}

double region_peened_area(const RegionSet& regions, std::size_t r, std::span<const double> peened) {
    if (regions.excluded(r)) return 0.0;
    double area = 0.0;
    for (const RegionShare& s : regions.shares(r))
        area += coverage_weight(regions, r, s, peened) * regions.triangle_area_m2(static_cast<std::size_t>(s.triangle));
    return area;
}

double peened_coverage(const CoverageMap& coverage, std::span<const double> peened) {
    double covered = 0.0, area = 0.0;  // m2
    for (std::size_t t = 0; t < coverage.triangle_count(); ++t) {
        const double a = peened[t] * coverage.triangle_area(t);
        area += a;
        covered += a * coverage.coverage_of_triangle(t);
    }
    return area > 0.0 ? covered / area : std::numeric_limits<double>::quiet_NaN();
}

RegionStats region_stats(const RegionSet& regions, std::size_t r, const RegionTally& tally, const CoverageMap* coverage,
                         std::span<const double> peened, double duration_s) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    RegionStats s;
    s.triangles = regions.shares(r).size();
    s.area_m2 = regions.area_m2(r);
    s.peened_area_m2 = region_peened_area(regions, r, peened);
    s.impacts = tally.impacts;
    const bool has_area = s.area_m2 > 0.0;
    s.impacts_per_mm2_s = has_area ? static_cast<double>(s.impacts) / (s.area_m2 * 1e6) / duration_s : nan;
    s.mean_normal_speed = s.impacts > 0 ? tally.speed_sum / static_cast<double>(s.impacts) : nan;
    s.max_normal_speed = tally.max_speed;
    s.energy_per_area = has_area ? tally.energy_J / s.area_m2 : nan;
    s.coverage = coverage != nullptr ? region_coverage(regions, r, *coverage, peened) : nan;
    return s;
}

}  // namespace peensim
