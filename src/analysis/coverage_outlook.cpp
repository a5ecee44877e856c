#include "analysis/coverage_outlook.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis/sample_mean.h"
#include "analysis/student_t.h"

namespace peensim {

CoverageOutlook coverage_outlook(const std::vector<CoveragePoint>& curve, std::span<const double> batch_dent_area) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    constexpr double inf = std::numeric_limits<double>::infinity();
    CoverageOutlook o;
    o.coverage = curve.empty() ? 0.0 : curve.back().coverage;
    o.k_per_s = o.k_relative_se = o.k_low_per_s = o.k_high_per_s = nan;
    o.time_to_98_s = o.time_to_98_low_s = o.time_to_98_high_s = o.run_multiple = nan;
    AvramiFit fit;
    try {
        fit = fit_avrami(curve);
    } catch (const std::invalid_argument&) {
        return o;  // no point with 0 < C < 1: k is undetermined
    }
    if (!(fit.k_per_s > 0.0)) return o;
    o.fitted = true;
    o.k_per_s = fit.k_per_s;
    double se = fit.k_standard_error_per_s / fit.k_per_s;
    double quantile = 1.959963984540054;  // normal 97.5 %: the fit alone
    const SampleMean batches = sample_mean(batch_dent_area);
    if (batches.count >= 2 && batches.mean > 0.0) {
        const double batch_se = batches.standard_error / batches.mean;
        quantile = student_t_two_sided_quantile(0.05, static_cast<double>(batches.count) - 1.0);
        se = std::max(se, batch_se);
    }
    o.k_relative_se = se;
    o.k_low_per_s = std::max(0.0, fit.k_per_s * (1.0 - quantile * se));
    o.k_high_per_s = fit.k_per_s * (1.0 + quantile * se);
    const double ln50 = std::log(50.0);
    o.time_to_98_s = ln50 / fit.k_per_s;
    o.time_to_98_low_s = ln50 / o.k_high_per_s;
    o.time_to_98_high_s = o.k_low_per_s > 0.0 ? ln50 / o.k_low_per_s : inf;
    const double last = curve.back().time_s;
    o.run_multiple = last > 0.0 ? o.time_to_98_s / last : nan;
    return o;
}

}  // namespace peensim
