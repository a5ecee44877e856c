#include "output/speed_histogram.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/byte_stream.h"

namespace peensim {
namespace {

// Guards against absurd bin counts (and against corrupt checkpoint bytes asking for them).
constexpr double kMaxBins = 1e8;
constexpr std::string_view kHistogramMagic = "PSHIST01";

}  // namespace

SpeedHistogram::SpeedHistogram(double bin_width_m_per_s, double upper_m_per_s) : bin_width_(bin_width_m_per_s) {
    if (!(bin_width_m_per_s > 0.0) || !std::isfinite(bin_width_m_per_s) || !(upper_m_per_s > 0.0) || !std::isfinite(upper_m_per_s)) {
        throw std::invalid_argument("speed histogram: bin width and upper end must be positive");
    }
    const double bins = std::round(upper_m_per_s / bin_width_m_per_s);
    if (bins < 1.0 || bins > kMaxBins) {
        throw std::invalid_argument("speed histogram: upper / bin width must give 1 to 1e8 bins");
    }
    bins_.assign(static_cast<std::size_t>(bins), 0);
}

void SpeedHistogram::add_finite(double v) {
    if (count_ == 0) {
        min_ = max_ = v;
    } else {
        min_ = std::min(min_, v);
        max_ = std::max(max_, v);
    }
    ++count_;
    add_to_sum(v);
    if (v < 0.0) {
        ++bins_.front();
        return;
    }
    const double index = v / bin_width_;
    if (index >= static_cast<double>(bins_.size())) {
        // v / w can round up to the bin count for v just below the upper end.
        if (v < upper_m_per_s()) {
            ++bins_.back();
        } else {
            ++overflow_;
        }
        return;
    }
    ++bins_[static_cast<std::size_t>(index)];
}

void SpeedHistogram::add_to_sum(double v) {
    const double t = sum_ + v;
    sum_correction_ += std::abs(sum_) >= std::abs(v) ? (sum_ - t) + v : (v - t) + sum_;
    sum_ = t;
}

double SpeedHistogram::mean() const {
    if (count_ == 0) return std::numeric_limits<double>::quiet_NaN();
    return (sum_ + sum_correction_) / static_cast<double>(count_);
}

double SpeedHistogram::min() const { return count_ == 0 ? std::numeric_limits<double>::quiet_NaN() : min_; }

double SpeedHistogram::max() const { return count_ == 0 ? std::numeric_limits<double>::quiet_NaN() : max_; }

double SpeedHistogram::percentile(double p) const {
    if (!(p >= 0.0 && p <= 100.0)) {
        throw std::invalid_argument("speed histogram: percentile must be in [0, 100], got " + std::to_string(p));
    }
    if (count_ == 0) return std::numeric_limits<double>::quiet_NaN();
    const double rank = p / 100.0 * static_cast<double>(count_);  // 1-based, continuous
    if (rank <= 0.0) return min_;
    double below = 0.0;  // values in the bins before the current one
    for (std::size_t i = 0; i < bins_.size(); ++i) {
        if (bins_[i] == 0) continue;
        const double in_bin = static_cast<double>(bins_[i]);
        if (below + in_bin >= rank) {
            const double fraction = (rank - below) / in_bin;
            const double v = (static_cast<double>(i) + fraction) * bin_width_;
            return std::clamp(v, min_, max_);
        }
        below += in_bin;
    }
    // The rank falls in the overflow bin [upper, max].
    const double fraction = std::min(1.0, (rank - below) / static_cast<double>(overflow_));
    const double upper = upper_m_per_s();
    return std::clamp(upper + fraction * (max_ - upper), min_, max_);
}

void SpeedHistogram::merge(const SpeedHistogram& other) {
    if (other.bin_width_ != bin_width_ || other.bins_.size() != bins_.size()) {
        throw std::invalid_argument("speed histogram: cannot merge histograms with other bins");
    }
    if (other.count_ > 0) {
        min_ = count_ == 0 ? other.min_ : std::min(min_, other.min_);
        max_ = count_ == 0 ? other.max_ : std::max(max_, other.max_);
    }
    for (std::size_t i = 0; i < bins_.size(); ++i) bins_[i] += other.bins_[i];
    overflow_ += other.overflow_;
    count_ += other.count_;
    non_finite_ += other.non_finite_;
    add_to_sum(other.sum_);
    sum_correction_ += other.sum_correction_;
}

std::string SpeedHistogram::serialize() const {
    std::uint64_t filled = 0;
    for (const auto c : bins_) filled += c != 0 ? 1 : 0;
    ByteWriter out;
    out.put_raw(kHistogramMagic);
    out.put<std::uint64_t>(bins_.size());
    out.put(bin_width_);
    out.put(count_);
    out.put(overflow_);
    out.put(non_finite_);
    out.put(sum_);
    out.put(sum_correction_);
    out.put(min_);
    out.put(max_);
    out.put(filled);
    for (std::size_t i = 0; i < bins_.size(); ++i) {
        if (bins_[i] == 0) continue;
        out.put<std::uint64_t>(i);
        out.put<std::uint64_t>(bins_[i]);
    }
    return out.bytes();
}

SpeedHistogram SpeedHistogram::deserialize(std::string_view bytes) {
    ByteReader in(bytes, "speed histogram checkpoint data is invalid");
    if (in.take(kHistogramMagic.size()) != kHistogramMagic) in.fail("wrong magic");
    const std::uint64_t bin_count = in.get<std::uint64_t>();
    const double width = in.get<double>();
    if (bin_count < 1 || static_cast<double>(bin_count) > kMaxBins || !(width > 0.0) || !std::isfinite(width)) {
        in.fail("bad bins");
    }
    SpeedHistogram h(width, static_cast<double>(bin_count) * width);
    if (h.bins_.size() != bin_count) in.fail("bad bins");
    h.count_ = in.get<std::uint64_t>();
    h.overflow_ = in.get<std::uint64_t>();
    h.non_finite_ = in.get<std::uint64_t>();
    h.sum_ = in.get<double>();
    h.sum_correction_ = in.get<double>();
    h.min_ = in.get<double>();
    h.max_ = in.get<double>();
    const std::uint64_t filled = in.get<std::uint64_t>();
    if (filled > bin_count) in.fail("more filled bins than bins");
    std::uint64_t total = h.overflow_;
    std::uint64_t previous = 0;
    for (std::uint64_t k = 0; k < filled; ++k) {
        const std::uint64_t index = in.get<std::uint64_t>();
        const std::uint64_t c = in.get<std::uint64_t>();
        if (index >= bin_count || (k > 0 && index <= previous) || c == 0) {
            in.fail("bad bin entry");
        }
        h.bins_[index] = c;
        total += c;
        previous = index;
    }
    if (!in.at_end()) in.fail("trailing bytes");
    if (total != h.count_) in.fail("bin counts do not add up to the count");
    return h;
}

}  // namespace peensim
