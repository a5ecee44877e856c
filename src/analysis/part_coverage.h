// The coverage map of a part for a shot (one rule for `analyze` and `trade`): sample spacing a fifth
// of the dent a 1 m/s impact leaves (eq. 10), coarsened in steps of 25 % while the mesh would need
// more than kMaxCoverageSamples samples; the dent grid sized for 30 m/s impacts.
#pragma once

#include <cstdint>
#include <memory>

#include "analysis/coverage_map.h"
#include "contact/dent.h"

namespace peensim {

inline constexpr double kDentsPerSpacing = 5.0;                   // coverage sampling: spacing = dent at 1 m/s / 5
inline constexpr double kLargestCoverageSpeed = 30.0;             // m/s, sizes the coverage map's dent grid
inline constexpr std::int64_t kMaxCoverageSamples = 200'000'000;  // samples per component at most (1 bit each: 25 MB)

// smallest_diameter_m, largest_diameter_m (m): the shot's (the same for one size; a mix's smallest
// sets the sampling, its largest the dent grid), shot_density_kg_per_m3 (kg/m3), yield_stress_pa
// (Pa) of the part's material.
inline std::unique_ptr<CoverageMap> part_coverage_map(const TriangleMesh& mesh, double smallest_diameter_m, double largest_diameter_m,
                                                      double shot_density_kg_per_m3, double yield_stress_pa) {
    double spacing = dent_diameter(smallest_diameter_m, shot_density_kg_per_m3, 1.0, yield_stress_pa) / kDentsPerSpacing;
    while (CoverageMap::samples_needed(mesh, spacing) > kMaxCoverageSamples) spacing *= 1.25;
    return std::make_unique<CoverageMap>(mesh, spacing,
                                         dent_diameter(largest_diameter_m, shot_density_kg_per_m3, kLargestCoverageSpeed, yield_stress_pa));
}

}  // namespace peensim
