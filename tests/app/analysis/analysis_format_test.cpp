// The numbers of the analysis tables and reports as text: printf's %g, an empty cell for NaN, and
// no "-0".
#include "app/analysis/analysis_format.h"

#include <gtest/gtest.h>

#include <cmath>

namespace peensim {
namespace {

TEST(AnalysisFormat, SignificantDigitsAsPrintfG) {
    EXPECT_EQ(fmt(0.5), "0.5");
    EXPECT_EQ(fmt(61.8234), "61.82");
    EXPECT_EQ(fmt(1234567.0), "1.235e+06");
    EXPECT_EQ(fmt(-1e-5), "-1e-05");
    EXPECT_EQ(fmt(2.0 / 3.0, 6), "0.666667");
}

TEST(AnalysisFormat, ANonexistentValueIsAnEmptyCell) {
    EXPECT_EQ(fmt(NAN), "");
    EXPECT_EQ(fmt(INFINITY), "");
}

TEST(AnalysisFormat, ZeroHasNoSign) {
    EXPECT_EQ(fmt(-0.0), "0");
    EXPECT_EQ(fmt(-0.0, 6), "0");
    EXPECT_EQ(fmt(0.0), "0");
    EXPECT_EQ(fmt(-1e-300 * 1e-300), "0");  // a product that underflows to -0
}

}  // namespace
}  // namespace peensim
