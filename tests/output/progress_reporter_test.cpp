#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>

#include "output/progress_reporter.h"

namespace peensim {
namespace {

TEST(ProgressReporterTest, DrawsPercentageAndEndsLineOnFinish) {
    std::ostringstream out;
    ProgressReporter progress(out, true);
    progress.update(0.25, 1.0, 10);
    const std::string first = out.str();
    EXPECT_EQ(first.front(), '\r');
    EXPECT_NE(first.find("25.0%"), std::string::npos) << first;
    EXPECT_NE(first.find("[#####...............]"), std::string::npos) << first;
    EXPECT_NE(first.find("sim 0.2500/1.0000 s"), std::string::npos) << first;
    EXPECT_EQ(first.find('\n'), std::string::npos);

    progress.update(0.5, 1.0, 20);  // within the rate limit: not drawn
    EXPECT_EQ(out.str(), first);

    progress.finish();  // draws the last state
    const std::string all = out.str();
    EXPECT_NE(all.find("50.0%"), std::string::npos) << all;
    EXPECT_EQ(std::count(all.begin(), all.end(), '\r'), 2);
    ASSERT_FALSE(all.empty());
    EXPECT_EQ(all.back(), '\n');

    progress.finish();
    progress.update(0.75, 1.0, 30);
    EXPECT_EQ(out.str(), all);
}

TEST(ProgressReporterTest, DisabledPrintsNothing) {
    std::ostringstream out;
    ProgressReporter progress(out, false);
    progress.update(0.1, 1.0, 1);
    progress.update(0.9, 1.0, 2);
    progress.finish();
    EXPECT_TRUE(out.str().empty());
}

TEST(ProgressReporterTest, FinishWithoutUpdatePrintsNothing) {
    std::ostringstream out;
    ProgressReporter progress(out, true);
    progress.finish();
    EXPECT_TRUE(out.str().empty());
}

}  // namespace
}  // namespace peensim
