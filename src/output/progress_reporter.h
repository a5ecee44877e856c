// The one-line progress bar on the terminal during a run, redrawn in place with '\r':
//   [##########..........]  50.0%  sim 0.2500/0.5000 s  ETA 1m23s  12345 impacts/s
// Redraws at most kProgressRedrawsPerSecond times a second, so calling update() every step
// costs one steady-clock read. The ETA and the impact rate are measured from the first
// update(), so a resumed run reports its own speed rather than that of the original run.
#pragma once

#include <chrono>
#include <cstdint>
#include <ostream>

namespace peensim {

// 1/s, upper bound on redraws: smooth for a human, negligible for the run.
inline constexpr double kProgressRedrawsPerSecond = 5.0;

class ProgressReporter {
public:
    // `enabled` is the caller's decision (e.g. stderr is a terminal and not --quiet); when
    // false nothing is ever written.
    ProgressReporter(std::ostream& out, bool enabled);

    // sim_time_s and duration_s in s; impacts counted since the run started.
    void update(double sim_time_s, double duration_s, std::uint64_t impacts);

    // Draws the last state given to update() and ends the line; does nothing if update()
    // was never called (or when disabled). Later calls do nothing.
    void finish();

private:
    using Clock = std::chrono::steady_clock;
    void draw(Clock::time_point now);

    std::ostream& out_;
    bool enabled_;
    bool started_ = false;  // update() called at least once
    bool finished_ = false;
    Clock::time_point first_update_{};
    Clock::time_point next_draw_{};
    double first_sim_time_s_ = 0.0;  // s
    std::uint64_t first_impacts_ = 0;
    double sim_time_s_ = 0.0;    // s, latest
    double duration_s_ = 0.0;    // s, latest
    std::uint64_t impacts_ = 0;  // latest
    int last_line_length_ = 0;   // chars, to blank out the rest of a longer previous line
};

}  // namespace peensim
