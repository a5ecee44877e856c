// Dent diameter, reference eq. 10: phi = D (8 rho V^2 / (9 sigma_y))^(1/4).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "contact/dent.h"

namespace peensim {
namespace {

TEST(AnalysisDent, MatchesHandComputedValue) {
    // D = 1 mm, rho = 7800 kg/m^3, V = 5 m/s, sigma_y = 1 GPa:
    // 8 * 7800 * 25 = 1.56e6; / (9 * 1e9) = 1.733333e-4; sqrt = 1.3165612e-2; sqrt = 0.11474150;
    // phi = 1 mm * 0.11474150 = 0.11474150 mm.
    EXPECT_NEAR(dent_diameter(1e-3, 7800.0, 5.0, 1e9), 0.11474150e-3, 1e-11);
}

TEST(AnalysisDent, ScalesAsSquareRootOfSpeedAndIgnoresSign) {
    const double slow = dent_diameter(2e-3, 7800.0, 2.0, 8e8);
    EXPECT_NEAR(dent_diameter(2e-3, 7800.0, 8.0, 8e8) / slow, 2.0, 1e-12);  // (4^2)^(1/4) = 2
    EXPECT_DOUBLE_EQ(dent_diameter(2e-3, 7800.0, -2.0, 8e8), slow);
    EXPECT_EQ(dent_diameter(2e-3, 7800.0, 0.0, 8e8), 0.0);
}

TEST(AnalysisDent, RejectsNonPositiveMaterialOrSize) {
    EXPECT_THROW(dent_diameter(0.0, 7800.0, 5.0, 1e9), std::invalid_argument);
    EXPECT_THROW(dent_diameter(1e-3, -1.0, 5.0, 1e9), std::invalid_argument);
    EXPECT_THROW(dent_diameter(1e-3, 7800.0, 5.0, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace peensim
