#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <stdexcept>
#include <vector>

#include "output/speed_histogram.h"

namespace peensim {
namespace {

// The nearest-rank percentile the histogram approximates: the ceil(p/100 n)-th smallest.
double nearest_rank(std::vector<double> values, double p) {
    std::sort(values.begin(), values.end());
    const auto rank = static_cast<std::size_t>(std::ceil(p / 100.0 * static_cast<double>(values.size())));
    return values[std::max<std::size_t>(rank, 1) - 1];
}

void expect_percentiles_within_a_bin(const SpeedHistogram& h, const std::vector<double>& values) {
    // Bin edges are computed in floating point: allow a hair over one bin width.
    const double tolerance = h.bin_width_m_per_s() * (1.0 + 1e-9);
    for (const double p : {0.5, 1.0, 10.0, 25.0, 50.0, 75.0, 90.0, 99.0, 100.0}) {
        EXPECT_NEAR(h.percentile(p), nearest_rank(values, p), tolerance) << "p" << p;
    }
}

TEST(SpeedHistogramTest, UniformValuesGivePercentilesWithinOneBin) {
    SpeedHistogram h;
    std::vector<double> values;
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> speed(0.0, 20.0);  // m/s
    for (int i = 0; i < 100000; ++i) values.push_back(speed(rng));
    for (const double v : values) h.add(v);

    EXPECT_EQ(h.count(), values.size());
    expect_percentiles_within_a_bin(h, values);
    EXPECT_NEAR(h.percentile(50.0), 10.0, 0.1);  // the distribution's own median
    EXPECT_EQ(h.max(), *std::max_element(values.begin(), values.end()));
    EXPECT_EQ(h.min(), *std::min_element(values.begin(), values.end()));
    EXPECT_EQ(h.percentile(0.0), h.min());
    EXPECT_EQ(h.percentile(100.0), h.max());
}

TEST(SpeedHistogramTest, KnownDistributionsMatchTheirSortedValues) {
    std::mt19937_64 rng(7);
    std::lognormal_distribution<double> lognormal(1.0, 0.5);  // m/s, skewed like impact speeds
    std::exponential_distribution<double> exponential(0.5);   // m/s, mean 2
    for (int which = 0; which < 2; ++which) {
        SpeedHistogram h;
        std::vector<double> values;
        for (int i = 0; i < 50000; ++i) {
            values.push_back(which == 0 ? lognormal(rng) : exponential(rng));
        }
        for (const double v : values) h.add(v);
        expect_percentiles_within_a_bin(h, values);
    }
}

TEST(SpeedHistogramTest, MeanIsExactAndSmallSetsInterpolate) {
    SpeedHistogram h(0.5, 10.0);  // coarse bins, to see the interpolation
    for (const double v : {1.0, 2.0, 3.0, 4.0}) h.add(v);
    EXPECT_DOUBLE_EQ(h.mean(), 2.5);
    // Rank 2 of 4 is the value 2.0, alone in bin [2.0, 2.5) and reached at its full count:
    // the estimate is the bin's upper end, one bin width off at most.
    EXPECT_DOUBLE_EQ(h.percentile(50.0), 2.5);
    // Rank 1 of 4 (p25) is 1.0; p12.5 is rank 0.5, halfway into the bin of 1.0.
    EXPECT_DOUBLE_EQ(h.percentile(25.0), 1.5);
    EXPECT_DOUBLE_EQ(h.percentile(12.5), 1.25);

    // 0.1 added a million times: a naive sum drifts, the compensated sum does not.
    SpeedHistogram many;
    for (int i = 0; i < 1000000; ++i) many.add(0.1);
    EXPECT_EQ(many.mean(), 0.1);
}

TEST(SpeedHistogramTest, OverflowKeepsTheMaximumAndNonFiniteIsSetAside) {
    SpeedHistogram h(0.001, 200.0);
    h.add(5.0);
    h.add(250.0);
    h.add(300.0);
    h.add(std::nan(""));
    h.add(INFINITY);
    EXPECT_EQ(h.count(), 3u);
    EXPECT_EQ(h.non_finite(), 2u);
    EXPECT_EQ(h.overflow_count(), 2u);
    EXPECT_EQ(h.max(), 300.0);
    EXPECT_EQ(h.percentile(100.0), 300.0);
    const double p50 = h.percentile(50.0);  // rank 1.5: halfway into the overflow bin
    EXPECT_GE(p50, 200.0);
    EXPECT_LE(p50, 300.0);
    EXPECT_NEAR(h.mean(), (5.0 + 250.0 + 300.0) / 3.0, 1e-12);
}

TEST(SpeedHistogramTest, EmptyAndBadArguments) {
    SpeedHistogram h;
    EXPECT_EQ(h.count(), 0u);
    EXPECT_TRUE(std::isnan(h.mean()));
    EXPECT_TRUE(std::isnan(h.percentile(50.0)));
    EXPECT_TRUE(std::isnan(h.max()));
    EXPECT_THROW(h.percentile(-1.0), std::invalid_argument);
    EXPECT_THROW(h.percentile(100.5), std::invalid_argument);
    EXPECT_THROW(SpeedHistogram(0.0, 1.0), std::invalid_argument);
    EXPECT_THROW(SpeedHistogram(0.001, -1.0), std::invalid_argument);
}

TEST(SpeedHistogramTest, MergeEqualsAddingEverythingToOne) {
    SpeedHistogram a, b, all;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> speed(0.0, 250.0);  // m/s, some overflow
    for (int i = 0; i < 20000; ++i) {
        const double v = speed(rng);
        (i % 3 == 0 ? a : b).add(v);
        all.add(v);
    }
    a.merge(b);
    EXPECT_EQ(a.count(), all.count());
    EXPECT_EQ(a.overflow_count(), all.overflow_count());
    EXPECT_EQ(a.min(), all.min());
    EXPECT_EQ(a.max(), all.max());
    EXPECT_NEAR(a.mean(), all.mean(), 1e-12 * all.mean());
    for (const double p : {10.0, 50.0, 90.0}) EXPECT_EQ(a.percentile(p), all.percentile(p));

    SpeedHistogram empty;
    empty.merge(all);
    EXPECT_EQ(empty.min(), all.min());
    EXPECT_THROW(a.merge(SpeedHistogram(0.01, 200.0)), std::invalid_argument);
}

TEST(SpeedHistogramTest, SerializationRoundTripsExactly) {
    SpeedHistogram h;
    std::mt19937_64 rng(11);
    std::lognormal_distribution<double> speed(1.5, 0.8);
    for (int i = 0; i < 10000; ++i) h.add(speed(rng));
    h.add(1000.0);
    h.add(std::nan(""));

    const std::string bytes = h.serialize();
    EXPECT_LT(bytes.size(), 16u * 10000u + 200u);  // sparse: only filled bins
    const SpeedHistogram back = SpeedHistogram::deserialize(bytes);
    EXPECT_EQ(back, h);
    EXPECT_EQ(back.mean(), h.mean());
    EXPECT_EQ(back.percentile(90.0), h.percentile(90.0));
    EXPECT_EQ(back.serialize(), bytes);

    const SpeedHistogram empty_back = SpeedHistogram::deserialize(SpeedHistogram(0.01, 50.0).serialize());
    EXPECT_EQ(empty_back.count(), 0u);
    EXPECT_EQ(empty_back.bin_width_m_per_s(), 0.01);
    EXPECT_DOUBLE_EQ(empty_back.upper_m_per_s(), 50.0);
}

TEST(SpeedHistogramTest, CorruptBytesAreRejected) {
    SpeedHistogram h;
    h.add(3.0);
    const std::string bytes = h.serialize();
    EXPECT_THROW(SpeedHistogram::deserialize(""), std::runtime_error);
    EXPECT_THROW(SpeedHistogram::deserialize(bytes.substr(0, bytes.size() - 1)), std::runtime_error);
    EXPECT_THROW(SpeedHistogram::deserialize(bytes + "x"), std::runtime_error);
    std::string wrong_magic = bytes;
    wrong_magic[0] = 'X';
    EXPECT_THROW(SpeedHistogram::deserialize(wrong_magic), std::runtime_error);
    std::string wrong_count = bytes;
    wrong_count[8 + 16] ^= 1;  // the count field: no longer the sum of the bins
    EXPECT_THROW(SpeedHistogram::deserialize(wrong_count), std::runtime_error);
}

}  // namespace
}  // namespace peensim
