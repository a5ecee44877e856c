// The mean of a sample and its standard error, over its finite values (a batch without impacts has
// no mean speed, a run without a fit no time to 98 %: they are left out).
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

namespace peensim {

struct SampleMean {
    double mean = std::numeric_limits<double>::quiet_NaN();
    double standard_error = std::numeric_limits<double>::quiet_NaN();  // sd / sqrt(n); NaN with fewer than two values
    std::size_t count = 0;                                             // finite values
};

inline SampleMean sample_mean(std::span<const double> values) {
    SampleMean s;
    double sum = 0.0;
    for (double v : values)
        if (std::isfinite(v)) sum += v, ++s.count;
    if (s.count == 0) return s;
    const double n = static_cast<double>(s.count);
    s.mean = sum / n;
    if (s.count < 2) return s;
    double sq = 0.0;
    for (double v : values)
        if (std::isfinite(v)) sq += (v - s.mean) * (v - s.mean);
    s.standard_error = std::sqrt(sq / (n - 1.0) / n);
    return s;
}

}  // namespace peensim
