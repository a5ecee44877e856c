#include "analysis/coverage_progress.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "common/float_limits.h"

namespace peensim {

CoverageProgress::CoverageProgress(std::unique_ptr<CoverageMap> map, SampleClasses classes, double target)
    : map_(std::move(map)), classes_(std::move(classes)), target_(target) {
    std::size_t regions = 0;
    for (std::size_t k = 0; k < classes_.size(); ++k)
        for (std::uint32_t r : classes_.info(static_cast<std::uint16_t>(k)).regions) regions = std::max<std::size_t>(regions, r + 1);
    regions = std::max(regions, classes_.region_count());
    areas_of_class_.assign(classes_.size(), {});
    area_m2_.assign(regions + 2, 0.0);
    const std::uint32_t rest = static_cast<std::uint32_t>(regions + 1);
    for (std::size_t k = 0; k < classes_.size(); ++k) {
        const auto kk = static_cast<std::uint16_t>(k);
        const SampleClass& c = classes_.info(kk);
        if (c.peened()) areas_of_class_[k].push_back(0);
        bool counted = false;
        for (std::uint32_t r : c.regions) {
            if (classes_.counts(kk, r)) areas_of_class_[k].push_back(r + 1);
            counted = counted || !classes_.region_excluded(r);
        }
        if (c.peened() && !counted) {
            areas_of_class_[k].push_back(rest);
            area_m2_[rest] += c.area_m2;
        }
    }
    area_m2_[0] = classes_.peened_area_m2();
    for (std::size_t r = 0; r < regions; ++r) area_m2_[r + 1] = classes_.region_counted_area_m2(r);
    covered_m2_.assign(area_m2_.size(), 0.0);
    reached_at_.assign(area_m2_.size(), kNaN);
    covered_peened_.assign(map_->triangle_count(), 0);
}

void CoverageProgress::cover(std::uint16_t k, double m2, double time_s) {
    for (std::uint32_t a : areas_of_class_[k]) {
        covered_m2_[a] += m2;
        if (std::isnan(reached_at_[a]) && covered_m2_[a] >= target_ * area_m2_[a]) reached_at_[a] = time_s;
    }
}

void CoverageProgress::add_dent(const Vec3& centre, double diameter_m, double time_s) {
    map_->add_dent(centre, diameter_m, [&](std::size_t t, std::int64_t first, std::uint64_t bits) {
        const double area = map_->sample_area(t);
        const std::uint16_t uniform = classes_.triangle_class(t);
        if (uniform != SampleClasses::kMixed) {
            const int n = std::popcount(bits);
            cover(uniform, area * n, time_s);
            if (classes_.info(uniform).peened()) covered_peened_[t] += n;
            return;
        }
        for (; bits != 0; bits &= bits - 1) {
            const std::uint16_t k = classes_.class_of(t, first + std::countr_zero(bits));
            cover(k, area, time_s);
            if (classes_.info(k).peened()) ++covered_peened_[t];
        }
    });
}

double CoverageProgress::share(std::size_t area) const {
    return area_m2_[area] > 0.0 ? std::min(1.0, covered_m2_[area] / area_m2_[area]) : kNaN;
}

double CoverageProgress::triangle_coverage(std::size_t t) const {
    const std::int64_t peened = classes_.peened_samples(t);
    return peened > 0 ? static_cast<double>(covered_peened_[t]) / static_cast<double>(peened) : kNaN;
}

}  // namespace peensim
