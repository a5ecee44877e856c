#include "app/analysis/coverage_verdict.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/float_limits.h"

namespace peensim {

namespace {

bool known(const AreaForecast& f) { return f.status == AreaForecast::Status::reached || f.status == AreaForecast::Status::forecast; }
}  // namespace

PeenedAreas peened_areas(const ComponentAnalysis& c) {
    PeenedAreas a;
    if (!c.coverage) return a;
    const SampleClasses& classes = c.coverage->classes();
    for (std::size_t k = 0; k < classes.size(); ++k) {
        const SampleClass& s = classes.info(static_cast<std::uint16_t>(k));
        a.total_m2 += s.area_m2;
        if (s.excluded)
            a.excluded_m2 += s.area_m2;
        else if (!s.reachable)
            a.unreachable_m2 += s.area_m2;
        else
            a.peened_m2 += s.area_m2;
    }
    return a;
}

double share_below(const ComponentAnalysis& c, double target) {
    if (!c.coverage) return kNaN;
    const CoverageMap& map = c.coverage->map();
    const SampleClasses& classes = c.coverage->classes();
    double below = 0.0, area = 0.0;  // m2
    for (std::size_t t = 0; t < map.triangle_count(); ++t) {
        const double a = static_cast<double>(classes.peened_samples(t)) * map.sample_area(t);
        if (!(a > 0.0)) continue;
        area += a;
        if (c.coverage->triangle_coverage(t) < target) below += a;
    }
    return area > 0.0 ? below / area : kNaN;
}

Everywhere everywhere(const ComponentAnalysis& c) {
    Everywhere e;
    e.uniformity = e.uniformity_low = e.uniformity_high = e.coverage_min = e.coverage_mean = kNaN;
    if (!c.coverage) return e;
    const SampleClasses& classes = c.coverage->classes();
    double covered = 0.0, area = 0.0;  // m2
    for (std::size_t r = 0; r < c.regions.size(); ++r) {
        const double peened = classes.region_peened_area_m2(r);
        if (c.regions.excluded(r) || !(peened > 0.0)) continue;
        const double now = c.coverage->region_coverage(r);
        ++e.counted;
        covered += now * peened;
        area += peened;
        e.coverage_min = e.counted == 1 ? now : std::min(e.coverage_min, now);
    }
    if (area > 0.0) e.coverage_mean = covered / area;
    e.slowest = c.forecast.slowest_region;
    e.time = c.forecast.everywhere;
    const AreaForecast& whole = c.forecast.whole;
    if (e.counted > 0 && known(whole) && known(e.time) && e.time.time_s > 0.0) {
        e.uniformity = whole.time_s / e.time.time_s;
        e.uniformity_low = whole.low_s / e.time.high_s;
        e.uniformity_high = std::min(1.0, whole.high_s / e.time.low_s);
    }
    return e;
}

std::string slowest_area_name(const ComponentAnalysis& c, int slowest) {
    if (slowest == CoverageForecast::kRestOfPart) return c.regions.empty() ? c.name : "the rest of " + c.name + " (in no region)";
    return slowest >= 0 ? c.regions.name(static_cast<std::size_t>(slowest)) : std::string();
}

}  // namespace peensim
