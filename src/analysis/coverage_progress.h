// Coverage of a part's peened area as dents land: the coverage map (coverage_map.h) with its
// samples sorted into classes (sample_classes.h), and the covered area of every area that counts
// (the whole peened area, and every region) kept up to date dent by dent, with the moment each
// first reached the target. `peensim analyze` draws the coverage curves and takes the observed
// times to the target from it; `peensim run --until-coverage` watches it to stop the run.
// Pure computation: no file I/O.
#pragma once

#include <cmath>
#include <memory>
#include <vector>

#include "analysis/coverage_map.h"
#include "analysis/sample_classes.h"

namespace peensim {

// A point of a coverage curve.
struct CoveragePoint {
    double time_s = 0.0;    // s
    double coverage = 0.0;  // covered area fraction, 0..1
};

class CoverageProgress {
public:
    // target (0..1]: the coverage whose first moment each area records.
    CoverageProgress(std::unique_ptr<CoverageMap> map, SampleClasses classes, double target);

    // A dent of diameter_m (m) at centre (m, component frame), made at time_s (s, any clock: the
    // reached times are on it).
    void add_dent(const Vec3& centre, double diameter_m, double time_s);

    const CoverageMap& map() const { return *map_; }
    const SampleClasses& classes() const { return classes_; }
    double target() const { return target_; }

    // Covered share (0..1) of the peened area, of region r's counted area (its peened area; an
    // excluded region's reachable area), of triangle t's peened samples (NaN where there is none).
    double coverage() const { return share(0); }
    double region_coverage(std::size_t r) const { return share(r + 1); }
    // What a map shows for triangle t: the coverage of its peened samples, or of all its samples
    // when it has none (a triangle out of reach or excluded still shows the dents that fell on it).
    double shown_triangle_coverage(std::size_t t) const {
        const double c = triangle_coverage(t);
        return std::isfinite(c) ? c : map_->coverage_of_triangle(t);
    }
    // The share of triangle t's samples that coverage counts (reachable, not excluded), 0..1.
    double peened_share(std::size_t t) const {
        const std::int64_t n = map_->samples_of_triangle(t);
        return n > 0 ? static_cast<double>(classes_.peened_samples(t)) / static_cast<double>(n) : 0.0;
    }
    double triangle_coverage(std::size_t t) const;
    // When the peened area, region r reached the target (NaN: not yet).
    double reached_at_s() const { return reached_at_[0]; }
    double region_reached_at_s(std::size_t r) const { return reached_at_[r + 1]; }
    // The rest: the peened area in no region that is not excluded (all of it without regions),
    // its area (m2), coverage and when it reached the target.
    double rest_area_m2() const { return area_m2_.back(); }
    double rest_coverage() const { return share(area_m2_.size() - 1); }
    double rest_reached_at_s() const { return reached_at_.back(); }

private:
    double share(std::size_t area) const;
    void cover(std::uint16_t k, double m2, double time_s);

    std::unique_ptr<CoverageMap> map_;
    SampleClasses classes_;
    double target_ = 0.98;
    // Areas: 0 the peened area, 1 + r region r, the last the rest.
    std::vector<std::vector<std::uint32_t>> areas_of_class_;
    std::vector<double> area_m2_;               // m2
    std::vector<double> covered_m2_;            // m2
    std::vector<double> reached_at_;            // s (NaN: not yet)
    std::vector<std::int64_t> covered_peened_;  // per triangle: covered peened samples
};

}  // namespace peensim
