#include "analysis/jet_stream.h"

#include "analysis/warm_up.h"

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
    std::vector<double> shares(n);
    for (std::size_t k = 0; k < n; ++k) shares[k] = complete_[k].fast_share();
    const std::size_t best = mser_minimiser(shares, n - 2);
    if (best > n / 2) return std::nullopt;
    return complete_[best].first_impact;
}

}  // namespace peensim
