// Impact statistics of one region: what the impacts inside it (by their points) brought, and its
// coverage over the area it shares with each triangle. Pure computation: no file I/O, no printing.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "analysis/coverage_progress.h"
#include "analysis/regions.h"

namespace peensim {

// Time batches an analysis window is cut into for batch means (a confidence interval from one run).
inline constexpr int kFigureBatches = 10;

// What a region's impacts brought, summed while the log streams.
struct RegionTally {
    std::uint64_t impacts = 0;
    double speed_sum = 0.0;  // m/s, normal speeds summed
    double max_speed = 0.0;  // m/s
    double energy_J = 0.0;   // J, 1/2 m v_n^2 summed

    void add(double vn_m_per_s, double energy_J_of_impact) {
        ++impacts;
        speed_sum += vn_m_per_s;
        max_speed = vn_m_per_s > max_speed ? vn_m_per_s : max_speed;
        energy_J += energy_J_of_impact;
    }
};

struct RegionStats {
    std::size_t triangles = 0;         // with some of their area in the region
    double area_m2 = 0.0;              // m2
    double peened_area_m2 = 0.0;       // m2, the part of it coverage counts (reachable, not excluded; NaN without coverage)
    double unreachable_area_m2 = 0.0;  // m2, the part of it no shot can reach (NaN without coverage)
    std::uint64_t impacts = 0;
    double impacts_per_mm2_s = 0.0;  // 1/(mm2 s), impacts / area / duration (NaN for zero area)
    double mean_normal_speed = 0.0;  // m/s, over the region's impacts (NaN without impacts)
    double max_normal_speed = 0.0;   // m/s (0 without impacts)
    double energy_per_area = 0.0;    // J/m2, 1/2 m vn^2 delivered / area (NaN for zero area)
    double coverage = 0.0;           // 0..1 over the peened area (an excluded region: its reachable area; NaN without coverage)
};

// coverage: the component's coverage (its peened areas and their coverage), or nullptr (no
// yield stress); duration_s: the analysed time (s).
RegionStats region_stats(const RegionSet& regions, std::size_t r, const RegionTally& tally, const CoverageProgress* coverage,
                         double duration_s);
}  // namespace peensim
