#include "analysis/latest_crossing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace peensim {
namespace {

// An area forecast at tau_s whose jackknife replicates give its log a standard error of exactly
// `se` (replicates spread along a random direction, so that areas are nearly independent when
// there are many replicates).
AreaCrossing area(double tau_s, double se, int replicates, std::mt19937_64& rng) {
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<double> w(static_cast<std::size_t>(replicates));
    double mean = 0.0;
    for (double& v : w) v = normal(rng), mean += v / replicates;
    double ss = 0.0;
    for (double& v : w) v -= mean, ss += v * v;
    const double r = replicates;
    const double scale = se / std::sqrt((r - 1.0) / r * ss);  // the jackknife's variance is se^2
    AreaCrossing a;
    a.tau_s = tau_s;
    for (double v : w) a.replicate_s.push_back(tau_s * std::exp(scale * v));
    return a;
}

TEST(LatestCrossing, OneAreaIsItsOwn) {
    std::mt19937_64 rng(1);
    AreaCrossing a = area(1000.0, 0.05, 10, rng);
    a.process_sd_s = 7.0;
    const LatestCrossing l = latest_crossing(std::vector<AreaCrossing>{a});
    EXPECT_EQ(l.mean_s, 1000.0);
    EXPECT_EQ(l.sd_s, 7.0);
    EXPECT_EQ(l.chance_excess_s, 0.0);
    ASSERT_EQ(l.last_share.size(), 1u);
    EXPECT_EQ(l.last_share[0], 1.0);
}

// Twenty areas forecast alike at 1000 s, each with an independent 5 % error: the latest of their
// forecasts is late by the mean of the largest of 20 standard normals, 1.8675 of that error, and
// that is the excess taken off. Then forecasts that scatter as their errors say (40 sets): the
// latest forecast is 9 % late on average, everywhere the common time.
TEST(LatestCrossing, TwentyAreasAlikeLoseTheWinnersCurse) {
    std::mt19937_64 rng(2);
    std::vector<AreaCrossing> areas;
    for (int a = 0; a < 20; ++a) areas.push_back(area(1000.0, 0.05, 400, rng));
    const LatestCrossing l = latest_crossing(areas);
    EXPECT_NEAR(l.chance_excess_s, 1.8675 * 0.05 * 1000.0, 0.06 * 1.8675 * 0.05 * 1000.0);
    EXPECT_NEAR(l.mean_s, 1000.0 - l.chance_excess_s, 1e-9);
    double shares = 0.0;
    for (double s : l.last_share) shares += s;
    EXPECT_NEAR(shares, 1.0, 1e-9);

    std::normal_distribution<double> normal(0.0, 1.0);
    const int sets = 40;
    double sum = 0.0, sum_latest = 0.0;
    for (int set = 0; set < sets; ++set) {
        std::vector<AreaCrossing> scattered;
        double latest = 0.0;
        for (int a = 0; a < 20; ++a) {
            scattered.push_back(area(1000.0 * (1.0 + 0.05 * normal(rng)), 0.05, 40, rng));
            latest = std::max(latest, scattered.back().tau_s);
        }
        sum += latest_crossing(scattered).mean_s, sum_latest += latest;
    }
    std::printf("twenty alike: the latest forecast %+.2f %%, everywhere %+.2f %% of the common time over %d sets\n",
                100.0 * (sum_latest / sets / 1000.0 - 1.0), 100.0 * (sum / sets / 1000.0 - 1.0), sets);
    EXPECT_GT(sum_latest / sets, 1070.0);
    EXPECT_NEAR(sum / sets, 1000.0, 15.0);
}

// Without estimation error (replicates all equal) there is nothing to take off; the run's own
// noise still makes the latest of two alike later than either (by sd / sqrt(pi) for two).
TEST(LatestCrossing, ExactForecastsOnlyTheRunsOwnNoise) {
    AreaCrossing a;
    a.tau_s = 1000.0;
    a.process_sd_s = 10.0;
    a.replicate_s.assign(10, 1000.0);
    const LatestCrossing l = latest_crossing(std::vector<AreaCrossing>{a, a});
    EXPECT_NEAR(l.chance_excess_s, 0.0, 1e-9);
    EXPECT_NEAR(l.mean_s, 1000.0 + 10.0 / std::sqrt(M_PI), 0.6);
}

// One area clearly the slowest (30 % later than nineteen alike, each 5 % uncertain): it is last in
// every draw, and the excess is nothing (antithetic draws cancel its own error exactly).
TEST(LatestCrossing, AClearlySlowestAreaKeepsItsForecast) {
    std::mt19937_64 rng(3);
    std::vector<AreaCrossing> areas;
    for (int a = 0; a < 19; ++a) areas.push_back(area(1000.0, 0.05, 10, rng));
    areas.push_back(area(1300.0, 0.05, 10, rng));
    const LatestCrossing l = latest_crossing(areas);
    EXPECT_GT(l.last_share.back(), 0.999);
    EXPECT_LT(l.chance_excess_s, 0.002 * 1300.0);
    EXPECT_NEAR(l.mean_s, 1300.0, 0.003 * 1300.0);
}

}  // namespace
}  // namespace peensim
