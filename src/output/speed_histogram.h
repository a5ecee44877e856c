// Distribution of normal impact speeds on a component, kept as fixed-width bin counts so a
// run of any length gives percentiles without holding its impacts.
//
// Accuracy: mean() is exact up to rounding (compensated running sum of the values). min()
// and max() are exact. percentile(p) interpolates linearly inside the bin that holds the
// nearest-rank percentile (the ceil(p/100 * count)-th smallest value) and is clamped to
// [min, max], so for values below upper_m_per_s() it differs from that value by less than one
// bin width. Above upper_m_per_s() all values share one overflow bin whose estimate is
// interpolated between upper_m_per_s() and max() (exact at p = 100 only).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace peensim {

// m/s, bin width: the percentile resolution, fine next to the speeds that matter (~1-20 m/s).
inline constexpr double kSpeedHistogramBinWidth_m_per_s = 0.001;
// m/s, upper end of the binned range; faster impacts go to the overflow bin.
inline constexpr double kSpeedHistogramUpper_m_per_s = 200.0;

class SpeedHistogram {
public:
    // Bins [i*w, (i+1)*w) for i < round(upper/w). Throws std::invalid_argument for a
    // non-positive or non-finite width or upper, or more than 100 million bins.
    explicit SpeedHistogram(double bin_width_m_per_s = kSpeedHistogramBinWidth_m_per_s,
                            double upper_m_per_s = kSpeedHistogramUpper_m_per_s);

    // Records a speed (m/s). Negative speeds count in the first bin (min() keeps the value);
    // NaN and infinities are not part of the statistics and only counted in non_finite().
    void add(double v_m_per_s) {
        if (!std::isfinite(v_m_per_s)) {
            ++non_finite_;
            return;
        }
        add_finite(v_m_per_s);
    }

    std::uint64_t count() const { return count_; }  // finite values added
    std::uint64_t non_finite() const { return non_finite_; }
    std::uint64_t overflow_count() const { return overflow_; }  // values >= upper_m_per_s()

    // m/s; NaN when count() == 0.
    double mean() const;
    double min() const;
    double max() const;
    // m/s, p in percent [0, 100]; NaN when count() == 0. Throws std::invalid_argument for p
    // outside [0, 100]. See the accuracy note at the top of this file.
    double percentile(double p) const;

    // Adds the other histogram's values. Throws std::invalid_argument when the bins differ.
    void merge(const SpeedHistogram& other);

    double bin_width_m_per_s() const { return bin_width_; }
    double upper_m_per_s() const { return static_cast<double>(bins_.size()) * bin_width_; }

    // Compact bytes (little-endian, common/byte_stream.h; only non-empty bins) for a
    // checkpoint; deserialize() throws std::runtime_error on anything that is not such bytes.
    std::string serialize() const;
    static SpeedHistogram deserialize(std::string_view bytes);

    friend bool operator==(const SpeedHistogram&, const SpeedHistogram&) = default;

private:
    void add_finite(double v_m_per_s);
    void add_to_sum(double v);

    double bin_width_;                 // m/s
    std::vector<std::uint64_t> bins_;  // counts per bin
    std::uint64_t overflow_ = 0;
    std::uint64_t count_ = 0;
    std::uint64_t non_finite_ = 0;
    double sum_ = 0.0;           // m/s, running sum of the values
    double sum_correction_ = 0;  // m/s, rounding lost from sum_ (Neumaier summation)
    double min_ = 0.0;           // m/s, valid when count_ > 0
    double max_ = 0.0;           // m/s, valid when count_ > 0
};

}  // namespace peensim
