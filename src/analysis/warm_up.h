// The end of a run's start-up transient, measured from its impact times: the MSER-5 rule (White
// 1997; Franklin and White 2008). The impacts are counted in equal bins, five bins make a batch,
// and the warm-up is the number of leading batches whose removal leaves the remaining batch means
// with the smallest standard error of their mean, SSE(d) / (m - d)^2. A chamber started from rest
// fills with moving shot and settles to a steady impact rate; the batches before that pull the
// mean away and are cut. Pure computation.
#pragma once

#include <cstddef>
#include <optional>
#include <span>

namespace peensim {

// The MSER statistic's minimiser over d = 0 .. last_d for a series y[0..n):
//   MSER(d) = sum_{i >= d} (y_i - mean_d)^2 / (n - d)^2,
// the first minimum (a later one must be smaller by more than 1e-15). The jet's steady start
// (jet_stream.h) and the run's warm-up below both use it.
std::size_t mser_minimiser(std::span<const double> y, std::size_t last_d);

// MSER-5's truncation for batch means y[0..m): the number of leading batches to drop (d up to
// m - 5: the last few batches alone always look steady). nullopt when it falls in the second half
// (the series is too short to show where the transient ends: White's rule for a failed
// truncation) or m < 10.
std::optional<std::size_t> mser_truncation(std::span<const double> batch_means);

struct WarmUp {
    double warm_up_s = 0.0;  // s, the measured transient: the dropped batches' length (at least one batch)
    double batch_s = 0.0;    // s, a batch's length, the resolution of the measurement
    std::size_t batches = 0;
};

inline constexpr std::size_t kWarmUpBatches = 100;  // batches of the series (each of 5 bins)

// The warm-up of a run from its impact times (s, any order) within [0, span_s): kWarmUpBatches
// batches of 5 bins of span_s / 500. nullopt when MSER fails (see above).
std::optional<WarmUp> measure_warm_up(std::span<const double> impact_times_s, double span_s);

}  // namespace peensim
