// Impact statistics of one region: what the impacts inside it (by their points) brought, and its
// coverage over the area it shares with each triangle. Pure computation: no file I/O, no printing.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "analysis/coverage_map.h"
#include "analysis/regions.h"

namespace peensim {

// Time batches an analysis window is cut into for batch means (a confidence interval from one run).
inline constexpr int kFigureBatches = 10;

// What a region's impacts brought, summed while the log streams.
struct RegionTally {
    std::uint64_t impacts = 0;
    double speed_sum = 0.0;                                   // m/s, normal speeds summed
    double max_speed = 0.0;                                   // m/s
    double energy_J = 0.0;                                    // J, 1/2 m v_n^2 summed
    std::array<double, kFigureBatches> batch_dent_area_m2{};  // m2 of dents delivered per time batch

    void add(double vn_m_per_s, double energy_J_of_impact, double dent_area_m2, int batch) {
        ++impacts;
        speed_sum += vn_m_per_s;
        max_speed = vn_m_per_s > max_speed ? vn_m_per_s : max_speed;
        energy_J += energy_J_of_impact;
        batch_dent_area_m2[static_cast<std::size_t>(batch)] += dent_area_m2;
    }
};

struct RegionStats {
    std::size_t triangles = 0;    // with some of their area in the region
    double area_m2 = 0.0;         // m2
    double peened_area_m2 = 0.0;  // m2, the part of it coverage counts (reachable, not excluded)
    std::uint64_t impacts = 0;
    double impacts_per_mm2_s = 0.0;  // 1/(mm2 s), impacts / area / duration (NaN for zero area)
    double mean_normal_speed = 0.0;  // m/s, over the region's impacts (NaN without impacts)
    double max_normal_speed = 0.0;   // m/s (0 without impacts)
    double energy_per_area = 0.0;    // J/m2, 1/2 m vn^2 delivered / area (NaN for zero area)
    double coverage = 0.0;           // 0..1 over the peened area (an excluded region: its whole area; NaN without a coverage map)
};

// The weights coverage gives region r's area on each of its triangles: its share, times the
// triangle's peened weight (reachable and not excluded) unless the region itself is excluded (then
// its whole area: its coverage is reported for information).
double region_coverage(const RegionSet& regions, std::size_t r, const CoverageMap& coverage, std::span<const double> peened);
double region_peened_area(const RegionSet& regions, std::size_t r, std::span<const double> peened);  // m2

// Coverage over the peened area of the whole component: sum of w_t c_t A_t / sum of w_t A_t (w: peened weights).
double peened_coverage(const CoverageMap& coverage, std::span<const double> peened);

// coverage: the component's coverage map, or nullptr (no yield stress); duration_s: the analysed time (s).
RegionStats region_stats(const RegionSet& regions, std::size_t r, const RegionTally& tally, const CoverageMap* coverage,
                         std::span<const double> peened, double duration_s);

}  // namespace peensim
