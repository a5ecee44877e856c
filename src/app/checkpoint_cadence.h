// When a run writes its periodic checkpoint: at the first restart point after
// `output.checkpoint_interval` of wall time since the last checkpoint began (or since the run
// started). The run loop asks at every restart point; the clock is a parameter so that tests
// can drive the cadence with a fake one instead of waiting.
#pragma once

#include <functional>

namespace peensim {

// s of wall time since any fixed origin, never decreasing.
using WallClock = std::function<double()>;

// std::chrono::steady_clock in seconds (the wall clock of a real run).
WallClock steady_wall_clock();

class CheckpointCadence {
public:
    // Starts the first interval now.
    CheckpointCadence(double interval_s, WallClock clock);

    // Reads the clock. True when a checkpoint is due; the next interval then starts now, so the
    // time the checkpoint takes to write counts towards it (checkpoints come every interval, not
    // every interval plus a write).
    bool due();

private:
    double interval_s_;       // s of wall time between checkpoints
    WallClock clock_;
    double interval_start_s_; // s, clock reading when the current interval began
};

}  // namespace peensim
