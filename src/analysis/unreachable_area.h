// Where no shot reaches, and what shot would: the part's area out of reach (outside excluded
// regions), per region and whole, and the shot diameters that would reach half and 90 % of it.
// The diameters come from the very reach test coverage uses (model/facet_reach.h), asked again with
// a smaller shot: per point of the unreachable area (a deterministic subsample), the largest radius
// that touches it, bisected between R / 64 and R. A point no shot of R / 64 touches is closed off (a
// bore an axle fills): it counts as reached by no shot at all.
// Pure computation: no file I/O.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include "analysis/coverage_map.h"
#include "analysis/regions.h"
#include "analysis/sample_classes.h"

namespace peensim {

struct UnreachableArea {
    double area_m2 = 0.0;  // m2, out of the shot's reach (not in an excluded region)
    // The largest shot diameter (m) that reaches half / 90 % of that area (0: no shot reaches so
    // much of it: closed off; NaN: no area out of reach).
    double half_reached_by_m = std::numeric_limits<double>::quiet_NaN();
    double most_reached_by_m = std::numeric_limits<double>::quiet_NaN();
    std::size_t points = 0;  // points of it tested
};

struct UnreachableFindings {
    double shot_diameter_m = 0.0;          // m, the shot the run used (a mix's smallest)
    UnreachableArea whole;                 // the part
    std::vector<UnreachableArea> regions;  // per region (RegionSet order)
    std::vector<double> triangle_share;    // per triangle: the share of its area out of reach (0..1)
};

// Per triangle of the map the largest diameter that reaches each tested point is found with at most
// about max_points points over the whole part (their area shares the untested samples').
UnreachableFindings find_unreachable_area(const CoverageMap& map, const SampleClasses& classes, const RegionSet& regions,
                                          const ReachTest& reach, double shot_radius_m, std::size_t max_points = 600);

}  // namespace peensim
