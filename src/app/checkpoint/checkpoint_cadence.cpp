#include "app/checkpoint/checkpoint_cadence.h"

#include <chrono>
#include <utility>

namespace peensim {

WallClock steady_wall_clock() {
    return [] { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); };
}

CheckpointCadence::CheckpointCadence(double interval_s, WallClock clock)
    : interval_s_(interval_s), clock_(std::move(clock)), interval_start_s_(clock_()), last_point_s_(interval_start_s_) {}

bool CheckpointCadence::due() {
    const double now_s = clock_();
    const double spacing_s = now_s - last_point_s_;  // the next restart point is expected as far on
    last_point_s_ = now_s;
    if (now_s - interval_start_s_ < interval_s_ - 0.5 * spacing_s) return false;
    interval_start_s_ = now_s;
    return true;
}

}  // namespace peensim
