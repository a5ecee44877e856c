// The value a share of the area does not exceed: the maps' and ParaView's colour-scale top.
#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "analysis/area_percentile.h"

using peensim::area_percentile;

// A tiny triangle with a huge value does not set the top; the value whose cumulative area first
// reaches the share does.
TEST(AreaPercentile, ATinyOutlierDoesNotSetTheTop) {
    // (value, area): 97 % of the area at values <= 2, 2.9 % at 3, 0.1 % at 1000.
    const std::vector<std::pair<double, double>> v{{1000.0, 0.001}, {2.0, 0.47}, {1.0, 0.5}, {3.0, 0.029}};
    EXPECT_EQ(area_percentile(v, 0.98), 3.0);
    EXPECT_EQ(area_percentile(v, 0.97), 2.0);  // 0.5 + 0.47 reaches it exactly
    EXPECT_EQ(area_percentile(v, 0.5), 1.0);
    EXPECT_EQ(area_percentile(v, 1.0), 1000.0);
}

TEST(AreaPercentile, NoTrianglesGiveZero) { EXPECT_EQ(area_percentile({}, 0.98), 0.0); }
