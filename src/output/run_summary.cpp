#include "output/run_summary.h"

#include <utility>

namespace peensim {

NormalSpeedStats normal_speed_stats(std::string component, const SpeedHistogram& speeds) {
    NormalSpeedStats stats;
    stats.component = std::move(component);
    stats.count = speeds.count();
    stats.mean_m_per_s = speeds.mean();
    stats.p10_m_per_s = speeds.percentile(10.0);
    stats.p50_m_per_s = speeds.percentile(50.0);
    stats.p90_m_per_s = speeds.percentile(90.0);
    stats.max_m_per_s = speeds.max();
    return stats;
}

}  // namespace peensim
