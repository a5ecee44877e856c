// The Student's t helpers (analysis/student_t.h: the statistical tests and the sweep's confidence intervals), against tabulated values.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/student_t.h"

namespace peensim::testing {
namespace {

TEST(StudentT, QuantilesAndTailsAreTheTablesOnes) {
    EXPECT_NEAR(student_t_two_sided_quantile(0.05, 10.0), 2.228139, 1e-5);
    EXPECT_NEAR(student_t_two_sided_quantile(0.05, 30.0), 2.042272, 1e-5);
    EXPECT_NEAR(student_t_two_sided_quantile(0.01, 5.0), 4.032143, 1e-5);
    EXPECT_NEAR(student_t_two_sided_tail(1.0, 1.0), 0.5, 1e-12);                         // Cauchy: P(|T| > 1) = 1/2
    EXPECT_NEAR(student_t_two_sided_tail(2.0, 2.0), 1.0 - 2.0 / std::sqrt(6.0), 1e-12);  // closed form for 2 dof
    // Many degrees of freedom: the normal law.
    EXPECT_NEAR(student_t_two_sided_quantile(std::erfc(3.0 / std::sqrt(2.0)), 1e9), 3.0, 1e-6);
    EXPECT_NEAR(student_t_two_sided_tail(3.0, 1e5), std::erfc(3.0 / std::sqrt(2.0)), 1e-6);
}

TEST(StudentT, WelchDegreesOfFreedom) {
    EXPECT_DOUBLE_EQ(welch_dof(1.0, 16, 1.0, 16), 30.0);    // equal errors: n_a + n_b - 2
    EXPECT_NEAR(welch_dof(1.0, 16, 1e-6, 16), 15.0, 1e-9);  // one exact side: the other's n - 1
}

}  // namespace
}  // namespace peensim::testing
