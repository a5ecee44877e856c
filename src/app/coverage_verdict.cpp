#include "app/coverage_verdict.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace peensim {

PeenedAreas peened_areas(const ComponentAnalysis& c) {
    PeenedAreas a;
    for (std::size_t t = 0; t < c.fields->triangle_count(); ++t) {
        const double area = c.fields->area_m2(t);
        const double excluded = c.regions.excluded_fraction(t);
        const double reach = c.reach.empty() ? 1.0 : c.reach[t];
        a.total_m2 += area;
        a.excluded_m2 += excluded * area;
        a.unreachable_m2 += (1.0 - reach) * (1.0 - excluded) * area;
        a.peened_m2 += (c.peened.empty() ? 1.0 - excluded : c.peened[t]) * area;
    }
    return a;
}

double share_below(const ComponentAnalysis& c, double target) {
    if (!c.coverage) return std::numeric_limits<double>::quiet_NaN();
    double below = 0.0, area = 0.0;  // m2
    for (std::size_t t = 0; t < c.coverage->triangle_count(); ++t) {
        const double a = c.peened[t] * c.coverage->triangle_area(t);
        area += a;
        if (c.coverage->coverage_of_triangle(t) < target) below += a;
    }
    return area > 0.0 ? below / area : std::numeric_limits<double>::quiet_NaN();
}

Everywhere everywhere(const ComponentAnalysis& c) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    constexpr double inf = std::numeric_limits<double>::infinity();
    Everywhere e;
    e.time_to_98_s = e.time_to_98_high_s = e.uniformity = e.coverage_min = e.coverage_mean = nan;
    if (!c.coverage || c.region_outlooks.size() != c.regions.size()) return e;
    double k_sum = 0.0, k_min = inf, covered = 0.0, area = 0.0;
    int k_count = 0;
    double worst = -1.0;
    for (std::size_t r = 0; r < c.regions.size(); ++r) {
        const double peened = region_peened_area(c.regions, r, c.peened);
        if (c.regions.excluded(r) || !(peened > 0.0)) continue;
        const CoverageOutlook& o = c.region_outlooks[r];
        ++e.counted;
        covered += o.coverage * peened;
        area += peened;
        e.coverage_min = e.counted == 1 ? o.coverage : std::min(e.coverage_min, o.coverage);
        // A region at full coverage has nothing left to fit; one without an impact will never get there at this rate.
        const bool saturated = !o.fitted && o.coverage >= 1.0;
        const double k = o.fitted ? o.k_per_s : (saturated ? nan : 0.0);
        const double t98 = o.fitted ? o.time_to_98_s : (saturated ? 0.0 : inf);
        const double high = o.fitted ? o.time_to_98_high_s : (saturated ? 0.0 : inf);
        if (std::isfinite(k)) {
            k_sum += k;
            k_min = std::min(k_min, k);
            ++k_count;
        }
        if (t98 > worst) {
            worst = t98;
            e.least_covered = static_cast<int>(r);
        }
        e.time_to_98_high_s = std::isnan(e.time_to_98_high_s) ? high : std::max(e.time_to_98_high_s, high);
    }
    if (e.counted == 0) return e;
    e.time_to_98_s = worst;
    e.coverage_mean = covered / area;
    if (k_count > 0 && k_sum > 0.0) e.uniformity = k_min / (k_sum / k_count);
    return e;
}

}  // namespace peensim
