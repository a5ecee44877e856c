// The checkpoint cadence on a fake wall clock: due at the restart point nearest to the interval
// (the next one expected as far on as the last two were apart), the next interval starting from
// that checkpoint.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "app/checkpoint/checkpoint_cadence.h"

namespace peensim {
namespace {

// Clock readings (s) at which the cadence said "due", for restart points at `points_s`.
std::vector<double> checkpoints_at(double interval_s, const std::vector<double>& points_s) {
    double now_s = 0.0;
    CheckpointCadence cadence(interval_s, [&] { return now_s; });
    std::vector<double> written_s;
    for (double t : points_s) {
        now_s = t;
        if (cadence.due()) written_s.push_back(t);
    }
    return written_s;
}

TEST(CheckpointCadence, DueAtTheRestartPointNearestTheInterval) {
    // Points 0.4 s apart, a 2 s interval: 1.6 s and 2.4 s are 0.4 s either side; 2.0 s itself is one.
    EXPECT_EQ(checkpoints_at(2.0, {0.4, 0.8, 1.2, 1.6, 2.0, 2.4}), (std::vector<double>{2.0}));
    // Points at 1.5 s and 2.6 s: at 1.5 s the next is expected at 3.0 s, further from 2 s than it is.
    EXPECT_EQ(checkpoints_at(2.0, {0.5, 1.0, 1.5, 2.6}), (std::vector<double>{2.6}));
    // Points 0.5 s apart at 0.9, 1.4, 1.9 s: 1.9 s is 0.1 s early, the next (2.4 s) 0.4 s late.
    EXPECT_EQ(checkpoints_at(2.0, {0.4, 0.9, 1.4, 1.9, 2.4}), (std::vector<double>{1.9}));
    // Never much before the interval: the first point 1.9 s after the start (spacing 1.9 s) is
    // taken (the next is expected at 3.8 s), one at 0.9 s is not.
    EXPECT_EQ(checkpoints_at(2.0, {1.9}), (std::vector<double>{1.9}));
    EXPECT_TRUE(checkpoints_at(2.0, {0.9}).empty());
}

TEST(CheckpointCadence, ShortIntervalsWithinTenPercentOnADenseEventLoad) {
    // Restart points 0.3 s of wall time apart (the event-driven scheme on a dense load), a 2 s
    // interval: every checkpoint within 10 % of 2 s of the previous one. Waiting for the first
    // point after the interval gave 2.1 s - 2.4 s.
    std::vector<double> points_s;
    for (int k = 1; k <= 400; ++k) points_s.push_back(0.3 * k);
    const std::vector<double> written_s = checkpoints_at(2.0, points_s);
    ASSERT_GE(written_s.size(), 55u);  // 120 s of wall time
    double previous_s = 0.0;
    for (double t : written_s) {
        EXPECT_NEAR(t - previous_s, 2.0, 0.15 + 1e-9);
        previous_s = t;
    }
    // Each interval is the nearest the points allow (2.1 s: 1.8 s is further off), so no drift.
    EXPECT_NEAR(written_s.back() / static_cast<double>(written_s.size()), 2.1, 1e-9);
}

TEST(CheckpointCadence, IrregularRestartPointsStayWithinHalfTheLongestSpacing) {
    // Spacings drawn between 0.05 s and 0.4 s, a 10 s interval: never more than 0.4 s from it.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> spacing(0.05, 0.4);
    std::vector<double> points_s;
    for (double t = 0.0; t < 300.0;) points_s.push_back(t += spacing(rng));
    const std::vector<double> written_s = checkpoints_at(10.0, points_s);
    ASSERT_GE(written_s.size(), 29u);
    double previous_s = 0.0;
    for (double t : written_s) {
        EXPECT_NEAR(t - previous_s, 10.0, 0.4);
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
