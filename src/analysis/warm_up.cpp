#include "analysis/warm_up.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace peensim {

std::size_t mser_minimiser(std::span<const double> y, std::size_t last_d) {
    const std::size_t n = y.size();
    if (n == 0) return 0;
    last_d = std::min(last_d, n - 1);
    // From the last value back, so that each truncation costs O(1) (a run of hours makes millions
    // of the jet's windows).
    std::vector<double> mser(n, 0.0);
    double sum = 0.0, sum_sq = 0.0;
    for (std::size_t d = n; d-- > 0;) {
        sum += y[d];
        sum_sq += y[d] * y[d];
        const double m = static_cast<double>(n - d);
        mser[d] = std::max(0.0, sum_sq - sum * sum / m) / (m * m);
    }
    std::size_t best = 0;
    double best_mser = INFINITY;
    for (std::size_t d = 0; d <= last_d; ++d)
        if (mser[d] < best_mser - 1e-15) best_mser = mser[d], best = d;
    return best;
}

std::optional<std::size_t> mser_truncation(std::span<const double> y) {
    const std::size_t m = y.size();
    if (m < 10) return std::nullopt;
    const std::size_t best = mser_minimiser(y, m - 5);
    if (2 * best >= m) return std::nullopt;
    return best;
}

std::optional<WarmUp> measure_warm_up(std::span<const double> impact_times_s, double span_s) {
    constexpr std::size_t kBinsPerBatch = 5;
    const std::size_t bins = kWarmUpBatches * kBinsPerBatch;
    if (!(span_s > 0.0)) return std::nullopt;
    std::vector<double> counts(bins, 0.0);
    for (const double t : impact_times_s) {
        if (!(t >= 0.0) || !(t < span_s)) continue;
        const auto b = std::min(bins - 1, static_cast<std::size_t>(t / span_s * static_cast<double>(bins)));
        counts[b] += 1.0;
    }
    std::vector<double> batch_means(kWarmUpBatches, 0.0);
    for (std::size_t k = 0; k < kWarmUpBatches; ++k) {
        double s = 0.0;
        for (std::size_t j = 0; j < kBinsPerBatch; ++j) s += counts[k * kBinsPerBatch + j];
        batch_means[k] = s / kBinsPerBatch;
    }
    const std::optional<std::size_t> d = mser_truncation(batch_means);
    if (!d) return std::nullopt;
    WarmUp w;
    w.batch_s = span_s / kWarmUpBatches;
    w.batches = std::max<std::size_t>(*d, 1);
    w.warm_up_s = static_cast<double>(w.batches) * w.batch_s;
    return w;
}

}  // namespace peensim
