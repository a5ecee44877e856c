#include "analysis/jet_stream.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace peensim {

namespace {

void count(JetWindow& w, double time_s, bool fast, bool normal_kept) {
    ++w.impacts;
    w.end_time_s = time_s;
    w.fast += fast;
    w.normal_kept += normal_kept;
}

}  // namespace

JetStreamStats::JetStreamStats(double v0_m_per_s, std::uint64_t window) : v0_(v0_m_per_s), window_(window) {
    if (!(v0_m_per_s > 0.0) || window == 0)
        throw std::invalid_argument("JetStreamStats: expected v0 > 0 and a window of at least one impact");
}

void JetStreamStats::add(double time_s, double speed_m_per_s, double vn_m_per_s, double jet_normal_speed_m_per_s) {
    const bool fast = speed_m_per_s >= kKeptFraction * v0_;
    const bool normal_kept = vn_m_per_s >= kKeptFraction * jet_normal_speed_m_per_s;
    count(total_, time_s, fast, normal_kept);
    count(open_, time_s, fast, normal_kept);
    if (open_.impacts == window_) {
        complete_.push_back(open_);
        open_ = JetWindow{};
        open_.first_impact = total_.impacts;
    }
}

std::vector<JetWindow> JetStreamStats::windows() const {
    std::vector<JetWindow> out = complete_;
    if (open_.impacts) out.push_back(open_);
    return out;
}

double JetStreamStats::steady_fast_share() const {
    // The second half of the complete windows (or of everything, with fewer than two).
    if (complete_.size() < 2) return total_.fast_share();
    std::uint64_t fast = 0, n = 0;
    for (std::size_t k = complete_.size() / 2; k < complete_.size(); ++k) fast += complete_[k].fast, n += complete_[k].impacts;
    return static_cast<double>(fast) / static_cast<double>(n);
}

std::optional<std::uint64_t> JetStreamStats::steady_after() const {
    // MSER (White 1997, the warm-up rule of simulation output analysis): drop the first d windows
    // where that makes the standard error of the remaining windows' mean smallest,
    //   MSER(d) = sum_{i >= d} (x_i - mean_d)^2 / (n - d)^2.
    // A test of each window against a binomial band (used before) took impacts as independent; they
    // are not (a shot bounces several times, the jet crowds in bursts), so the windows of a steady
    // stream spread wider than binomial and a late window outside the band moved "steady" to the end
    // of the run. A minimum past the run's middle means the stream is still drifting: none.
    const std::size_t n = complete_.size();
    if (n < 4) return std::nullopt;
    // From the last window back, so that each truncation costs O(1): a run of hours makes millions
    // of windows.
    std::size_t best = 0;
    double best_mser = std::numeric_limits<double>::infinity(), sum = 0.0, sum_sq = 0.0;
    std::vector<double> mser(n, 0.0);
    for (std::size_t d = n; d-- > 0;) {
        const double x = complete_[d].fast_share();
        sum += x;
        sum_sq += x * x;
        const double m = static_cast<double>(n - d);
        mser[d] = std::max(0.0, sum_sq - sum * sum / m) / (m * m);
    }
    for (std::size_t d = 0; d + 1 < n; ++d)
        if (mser[d] < best_mser - 1e-15) best_mser = mser[d], best = d;
    if (best > n / 2) return std::nullopt;
    return complete_[best].first_impact;
}

}  // namespace peensim
