// When a run writes its periodic checkpoint: at the restart point nearest to
// `output.checkpoint_interval` of wall time since the last checkpoint began (or since the run
// started). The run loop asks at every restart point. Time stepping reaches one every step; the
// event-driven scheme only every work budget of events (a few tenths of a second of wall time on a
// dense load), so waiting for the first one after the interval made short intervals up to 20 %
// long (2 s: 2.0-2.4 s). The spacing of the last two restart points predicts the next one: a
// checkpoint is taken at this point when the interval is less than half a spacing away, which
// keeps it within half a spacing of the interval either way. The clock is a parameter so that
// tests can drive the cadence with a fake one instead of waiting.
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

    // Called at a restart point: reads the clock. True when a checkpoint is due; the next interval
    // then starts now, so the time the checkpoint takes to write counts towards it (checkpoints come
    // every interval, not every interval plus a write).
    bool due();

private:
    double interval_s_;  // s of wall time between checkpoints
    WallClock clock_;
    double interval_start_s_;  // s, clock reading when the current interval began
    double last_point_s_;      // s, clock reading at the previous restart point (or the start)
};

}  // namespace peensim
