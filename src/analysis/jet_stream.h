// How a nozzle's jet arrives on a component (conventional peening, reference section 4): of the
// impacts on it, the share arriving with at least 90 % of the nozzle's exit speed v0 (|v_in| >=
// 0.9 v0: the shot that met nothing on the way), and the share keeping 90 % of the jet's own normal
// speed there (v_n >= 0.9 v0 |d . n|, d the jet's axis, n the facet's normal), overall and per
// window of consecutive impacts; and from which impact on the stream is steady. Memory: one small
// record per window.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace peensim {

struct JetWindow {
    std::uint64_t first_impact = 0;  // 0-based index of its first impact on the component
    std::uint64_t impacts = 0;
    double end_time_s = 0.0;        // s, its last impact's time
    std::uint64_t fast = 0;         // |v_in| >= 0.9 v0
    std::uint64_t normal_kept = 0;  // v_n >= 0.9 of the jet's normal speed
    double fast_share() const { return impacts ? static_cast<double>(fast) / static_cast<double>(impacts) : 0.0; }
    double normal_kept_share() const { return impacts ? static_cast<double>(normal_kept) / static_cast<double>(impacts) : 0.0; }
};

class JetStreamStats {
public:
    static constexpr double kKeptFraction = 0.9;  // "arrives with at least 90 % of v0"

    // v0: the nozzle's exit speed (m/s); window: impacts per window (>= 1).
    JetStreamStats(double v0_m_per_s, std::uint64_t window);

    // One impact: time (s), speed |v_in| and normal speed v_n (m/s), and the jet's normal speed on
    // that facet, v0 |d . n| (m/s).
    void add(double time_s, double speed_m_per_s, double vn_m_per_s, double jet_normal_speed_m_per_s);

    double v0_m_per_s() const { return v0_; }
    std::uint64_t window() const { return window_; }
    std::uint64_t impacts() const { return total_.impacts; }
    const JetWindow& total() const { return total_; }
    // Complete windows, then the last partial one (if any impacts are left over).
    std::vector<JetWindow> windows() const;

    // The share of fast impacts over the steady part of the run (its second half of impacts).
    double steady_fast_share() const;
    // The first impact of the steady stream: the truncation of the complete windows that makes the
    // standard error of the remaining windows' mean fast share smallest (MSER); none when the run
    // has fewer than 4 complete windows or the best truncation lies past its middle (still drifting).
    std::optional<std::uint64_t> steady_after() const;

private:
    double v0_;
    std::uint64_t window_;
    JetWindow total_;
    std::vector<JetWindow> complete_;
    JetWindow open_;
};

}  // namespace peensim
