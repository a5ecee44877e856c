// Avrami fit of a coverage-versus-time curve: C(t) = 1 - exp(-k t) (reference, "Outputs the model
// must give"). With dents at random and a steady impact rate, A_r = k t and the law is exact.
#pragma once

#include <vector>

namespace peensim {

struct CoveragePoint {
    double time_s = 0.0;    // s
    double coverage = 0.0;  // covered area fraction, 0..1
};

struct AvramiFit {
    double k_per_s = 0.0;                 // 1/s, rate constant
    double k_standard_error_per_s = 0.0;  // 1/s, from the residuals (0 with a single usable point)
    double time_to_98_percent_s = 0.0;    // s, ln(50) / k: "100 %" coverage by the SAE J2277 convention
    bool extrapolated = false;            // time_to_98_percent_s lies beyond the last time given
    int points_used = 0;                  // points with t > 0 that entered the fit
};

// Fits k in two steps:
// 1. start: weighted least squares of y = -ln(1 - C) = k t through the origin, over points with
//    t > 0 and C < 1. If C carries a noise of constant variance, y's variance grows as 1/(1-C)^2, so
//    the weights are (1 - C)^2: points near saturation, where the log amplifies noise, count less.
// 2. refinement: Gauss-Newton on sum (C_i - (1 - exp(-k t_i)))^2 over all points with t > 0 (points
//    at C = 1 included), the least-squares fit in the quantity actually measured.
// The standard error is that of the refinement: s / sqrt(sum J_i^2), J_i = t_i exp(-k t_i),
// s^2 = residual sum of squares / (m - 1).
// Throws std::invalid_argument when no point has t > 0 and 0 < C < 1 (k is then undetermined).
AvramiFit fit_avrami(const std::vector<CoveragePoint>& points);

}  // namespace peensim
