// The checkpoint cadence on a fake wall clock: not due before the interval, due at the first
// restart point after it, the next interval starting from that checkpoint.
#include <gtest/gtest.h>

#include <vector>

#include "app/checkpoint_cadence.h"

namespace peensim {
namespace {

TEST(CheckpointCadence, DueOnlyOnceTheIntervalHasPassed) {
    double now_s = 100.0;
    CheckpointCadence cadence(2.0, [&] { return now_s; });
    now_s = 101.9;
    EXPECT_FALSE(cadence.due());
    now_s = 102.0;
    EXPECT_TRUE(cadence.due());
    EXPECT_FALSE(cadence.due());  // the next interval began at 102 s
    now_s = 103.5;
    EXPECT_FALSE(cadence.due());
    now_s = 104.25;  // a late restart point: the interval after it starts there, not at 104 s
    EXPECT_TRUE(cadence.due());
    now_s = 106.0;
    EXPECT_FALSE(cadence.due());
    now_s = 106.25;
    EXPECT_TRUE(cadence.due());
}

TEST(CheckpointCadence, FollowsWallTimeWhateverTheRestartPointsCost) {
    // Restart points 0.3 s of wall time apart (the slowest the event-driven scheme is meant to
    // reach them), a 10 s interval: every checkpoint within 10 % of 10 s of the previous one.
    double now_s = 0.0;
    CheckpointCadence cadence(10.0, [&] { return now_s; });
    std::vector<double> written_s;
    for (int k = 1; k <= 400; ++k) {
        now_s = 0.3 * k;
        if (cadence.due()) written_s.push_back(now_s);
    }
    ASSERT_EQ(written_s.size(), 11u);  // 120 s of wall time
    double previous_s = 0.0;
    for (double t : written_s) {
        EXPECT_GE(t - previous_s, 10.0);
        EXPECT_LE(t - previous_s, 10.0 + 0.3 + 1e-9);
        previous_s = t;
    }
}

TEST(CheckpointCadence, SteadyWallClockAdvances) {
    const WallClock clock = steady_wall_clock();
    const double a_s = clock();
    double b_s = clock();
    while (b_s == a_s) b_s = clock();
    EXPECT_GT(b_s, a_s);
}

}  // namespace
}  // namespace peensim
