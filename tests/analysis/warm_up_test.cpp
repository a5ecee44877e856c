// The MSER-5 warm-up (analysis/warm_up.h): exact truncation points on constructed series, the
// failure White's rule defines, and the transient of impact times drawn with a known start-up.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "analysis/warm_up.h"
#include "common/random.h"

namespace peensim {
namespace {

TEST(WarmUp, AConstantSeriesHasNoTransient) {
    const std::vector<double> y(100, 7.0);
    ASSERT_TRUE(mser_truncation(y).has_value());
    EXPECT_EQ(*mser_truncation(y), 0u);
}

TEST(WarmUp, ALevelShiftIsCutWhereItEnds) {
    // 12 high batches, then an alternating steady series: removing exactly the 12 leaves the
    // smallest SSE / n^2 (every steady batch is +-1 about the mean).
    std::vector<double> y;
    for (int i = 0; i < 12; ++i) y.push_back(30.0);
    for (int i = 0; i < 88; ++i) y.push_back(i % 2 ? 11.0 : 9.0);
    ASSERT_TRUE(mser_truncation(y).has_value());
    EXPECT_EQ(*mser_truncation(y), 12u);
}

TEST(WarmUp, ATransientIntoTheSecondHalfIsAFailure) {
    // The level changes at 70 of 100: the series is too short to show a steady state.
    std::vector<double> y;
    for (int i = 0; i < 70; ++i) y.push_back(30.0 + (i % 2));
    for (int i = 0; i < 30; ++i) y.push_back(10.0 + (i % 2));
    EXPECT_FALSE(mser_truncation(y).has_value());
    EXPECT_FALSE(mser_truncation(std::vector<double>(9, 1.0)).has_value());  // fewer than 10 batches
}

TEST(WarmUp, ImpactTimesWithAStartUpGiveItsLength) {
    // A Poisson stream of 1000 /s with 3000 /s in its first 0.2 s, over 4 s: batches of 0.04 s,
    // the transient 5 batches. MSER cuts 5 (or one either side, from the noise).
    Random rng(7);
    std::vector<double> times;
    double t = 0.0;
    while (t < 4.0) {
        const double rate = t < 0.2 ? 3000.0 : 1000.0;
        t += -std::log(1.0 - rng.uniform()) / rate;
        times.push_back(t);
    }
    const std::optional<WarmUp> w = measure_warm_up(times, 4.0);
    ASSERT_TRUE(w.has_value());
    EXPECT_DOUBLE_EQ(w->batch_s, 0.04);
    EXPECT_NEAR(w->warm_up_s, 0.2, 0.04 + 1e-12);
}

TEST(WarmUp, NoTransientStillCostsOneBatch) {
    // A replica started from rest needs some warm-up: the resolution of the measurement at least.
    Random rng(3);
    std::vector<double> times;
    for (double t = 0.0; t < 2.0;) times.push_back(t += -std::log(1.0 - rng.uniform()) / 2000.0);
    const std::optional<WarmUp> w = measure_warm_up(times, 2.0);
    ASSERT_TRUE(w.has_value());
    EXPECT_GE(w->warm_up_s, w->batch_s);
}

}  // namespace
}  // namespace peensim
