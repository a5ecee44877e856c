// The periodic checkpoints of a whole run (run_job in-process) follow the wall clock, driven here
// by a fake one so that the cadence is exact and the test never waits: with time stepping (a restart
// point at every step) a checkpoint comes every interval to within one step; with the event-driven
// scheme at the restart point nearest to the interval. Every checkpoint loads.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "app/checkpoint/checkpoint.h"
#include "app/run/run_job.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

constexpr double kIntervalS = 0.1;  // s of (fake) wall time, output.checkpoint_interval

// A fake wall clock that moves `tick_s` at every reading. At each reading it also takes away the
// checkpoint the run wrote since the previous one (loading it: it must be whole), noting when.
struct CheckpointWatch {
    struct Seen {
        double clock_s;      // s, fake wall time when it was found
        double simulated_s;  // s, simulated time it holds
    };
    CheckpointWatch(fs::path checkpoint, double tick) : file(std::move(checkpoint)), tick_s(tick) {}

    fs::path file;
    double tick_s;  // s of fake wall time per reading
    long readings = 0;
    std::vector<Seen> seen;

    double read() {
        if (fs::exists(file)) {
            seen.push_back({readings * tick_s, load_checkpoint(file.string()).state.time.seconds()});
            fs::remove(file);
        }
        return static_cast<double>(++readings) * tick_s;
    }
};

std::vector<CheckpointWatch::Seen> run_watched(const TestScene& scene, double tick_s) {
    const std::string dir = scene.make_subdirectory("out");
    CheckpointWatch watch(fs::path(dir) / kCheckpointFileName, tick_s);
    RunOptions o;
    o.scene_path = scene.scene_path();
    o.output_dir = dir;
    o.progress = false;
    o.analyze = false;
    o.overrides = {"output.checkpoint_interval=" + std::to_string(kIntervalS)};
    o.checkpoint_clock = [&watch] { return watch.read(); };
    std::ostringstream out, err;
    EXPECT_EQ(run_job(o, out, err), kExitOk) << err.str();
    std::cout << "[ cadence  ] " << scene.spec().scheme << ": " << watch.readings << " clock readings, " << watch.seen.size()
              << " checkpoints\n";
    return watch.seen;
}

TEST(RunCheckpoints, TimeSteppingCheckpointsEveryIntervalOfWallTime) {
    // ~600 steps, one (fake) millisecond each: a checkpoint every 100 steps. (The loop once looked
    // at the clock only every 1024 steps: this run would have had none.)
    const TestScene scene(small_rod_scene("step", 0.05));
    constexpr double kTickS = 1e-3;
    const std::vector<CheckpointWatch::Seen> seen = run_watched(scene, kTickS);
    ASSERT_GE(seen.size(), 4u);
    for (std::size_t k = 1; k < seen.size(); ++k) {
        const double gap_s = seen[k].clock_s - seen[k - 1].clock_s;
        EXPECT_GE(gap_s, kIntervalS - 1e-9) << k;
        EXPECT_LE(gap_s, kIntervalS + 2 * kTickS) << k;
        EXPECT_GT(seen[k].simulated_s, seen[k - 1].simulated_s) << k;
    }
}

TEST(RunCheckpoints, EventDrivenCheckpointsAtTheRestartPointNearestTheInterval) {
    // Restart points every 0.1 s of simulated time; the clock moves 0.04 s (fake) at each reading,
    // one per restart point: the nearest to the 0.1 s interval is 0.02 s off it either way.
    constexpr double kTickS = 0.04;
    const TestScene scene(small_rod_scene("event", 1.5));
    std::vector<CheckpointWatch::Seen> seen = run_watched(scene, kTickS);
    // The start's checkpoint (written before the loop, whatever the clock) is not the cadence's.
    ASSERT_FALSE(seen.empty());
    EXPECT_EQ(seen.front().simulated_s, 0.0);
    seen.erase(seen.begin());
    ASSERT_GE(seen.size(), 3u);
    for (std::size_t k = 0; k < seen.size(); ++k) {
        const CheckpointWatch::Seen& s = seen[k];
        EXPECT_NEAR(s.simulated_s * 10.0, std::round(s.simulated_s * 10.0), 1e-9) << "not at a restart point: " << s.simulated_s;
        if (k == 0) continue;
        EXPECT_NEAR(s.clock_s - seen[k - 1].clock_s, kIntervalS, 0.5 * kTickS + 1e-9) << s.simulated_s;
    }
}

}  // namespace
}  // namespace peensim::testing
