#include "analysis/jet_stream.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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
    if (!(v0_m_per_s > 0.0) || window == 0) throw std::invalid_argument("JetStreamStats: expected v0 > 0 and a window of at least one impact");
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
    if (complete_.size() < 4) return std::nullopt;
    const double p = steady_fast_share(), n = static_cast<double>(window_);
    // A share of 0 or 1 has no binomial spread: one impact of the window is the resolution.
    const double band = std::max(3.0 * std::sqrt(p * (1.0 - p) / n), 1.0 / n);
    std::size_t first = complete_.size();
    while (first > 0 && std::abs(complete_[first - 1].fast_share() - p) <= band) --first;
    if (first == complete_.size()) return std::nullopt;  // not even the last window is steady
    return complete_[first].first_impact;
}

}  // namespace peensim
