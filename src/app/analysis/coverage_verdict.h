// What the report concludes about a logged part's coverage, from its analysis: which of its area
// counts (the peened area: reachable and not excluded), the share still below the target, and
// "everywhere": the region that will be covered last, when, and how even the peening is.
#pragma once

#include <string>

#include "app/component_analysis.h"

namespace peensim {

struct PeenedAreas {
    double total_m2 = 0.0;        // m2, the whole surface
    double peened_m2 = 0.0;       // m2, the area coverage counts
    double excluded_m2 = 0.0;     // m2, in regions marked `exclude`
    double unreachable_m2 = 0.0;  // m2, out of the shot's reach (and not excluded)
};
// Needs the part's coverage (a yield stress).
PeenedAreas peened_areas(const ComponentAnalysis& c);

// The share of the peened area whose coverage (per triangle, over its peened samples) is below
// `target` (NaN without coverage).
double share_below(const ComponentAnalysis& c, double target);

struct Everywhere {
    int slowest = -1;   // the counted region that reaches the target last (CoverageForecast::kRestOfPart; -1: none)
    AreaForecast time;  // when every counted region has reached it (the forecast's `everywhere`)
    // The peened area's time to the target over everywhere's (1: the slowest region is no slower
    // than the part as a whole; NaN unless both are known), with its range from the two intervals.
    double uniformity = 0.0;
    double uniformity_low = 0.0;
    double uniformity_high = 0.0;
    double coverage_min = 0.0;   // of the counted regions now
    double coverage_mean = 0.0;  // area-weighted over the counted regions
    int counted = 0;             // regions counted: not excluded, with peened area
};
// Over the regions that are not excluded and have peened area; needs the forecast.
Everywhere everywhere(const ComponentAnalysis& c);

// The name of the area that reaches the target last: a region's, "the rest of the part" (its
// peened area in no region), or "" (none).
std::string slowest_area_name(const ComponentAnalysis& c, int slowest);

}  // namespace peensim
