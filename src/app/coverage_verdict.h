// What the report concludes about a logged part's coverage, from its analysis: which of its area
// counts (the peened area: reachable and not excluded), the share still below the target, and
// "everywhere": the region that will be covered last, when, and how even the peening is.
#pragma once

#include "app/component_analysis.h"

namespace peensim {

struct PeenedAreas {
    double total_m2 = 0.0;        // m2, the whole surface
    double peened_m2 = 0.0;       // m2, the area coverage counts
    double excluded_m2 = 0.0;     // m2, in regions marked `exclude`
    double unreachable_m2 = 0.0;  // m2, out of the shot's reach (and not excluded)
};
PeenedAreas peened_areas(const ComponentAnalysis& c);

// The share of the peened area whose coverage (per triangle) is below `target` (NaN without coverage).
double share_below(const ComponentAnalysis& c, double target);

struct Everywhere {
    int least_covered = -1;          // the counted region with the longest time to 98 % (-1: no region counts)
    double time_to_98_s = 0.0;       // s, its time: peening every counted region to 98 % (infinity: one has no impact yet)
    double time_to_98_high_s = 0.0;  // s, the largest upper bound of the counted regions' intervals
    double uniformity = 0.0;         // min / mean of the counted regions' Avrami rates k (1: even; NaN: none)
    double coverage_min = 0.0;       // of the counted regions now
    double coverage_mean = 0.0;      // area-weighted over the counted regions
    int counted = 0;                 // regions counted: not excluded, with peened area
};
// Over the regions that are not excluded and have peened area; needs the coverage outlooks.
Everywhere everywhere(const ComponentAnalysis& c);

}  // namespace peensim
