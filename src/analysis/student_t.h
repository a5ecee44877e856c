// Student's t distribution (the statistical tests, the sweep's confidence intervals), for comparisons of means whose standard errors are
// themselves estimated from few samples (16 columns, 10 batches): their ratio |difference| / SE follows t with (Welch-Satterthwaite)
// degrees of freedom, not the normal law, and its tails are much heavier (a 4.24 SE excess has a chance 2.2e-5 under the normal law, 2.3e-4
// under t with 30).
#pragma once

#include <cmath>
#include <limits>

namespace peensim {

// Regularized incomplete beta I_x(a, b), by its continued fraction (modified Lentz), on the side
// of x where it converges fast.
inline double incomplete_beta(double x, double a, double b) {
    if (x <= 0.0) return 0.0;
    if (x >= 1.0) return 1.0;
    if (x > (a + 1.0) / (a + b + 2.0)) return 1.0 - incomplete_beta(1.0 - x, b, a);
    const double log_front = a * std::log(x) + b * std::log1p(-x) - (std::lgamma(a) + std::lgamma(b) - std::lgamma(a + b));
    constexpr double tiny = 1e-300, eps = 1e-15;
    double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
    if (std::fabs(d) < tiny) d = tiny;
    d = 1.0 / d;
    double f = d;
    for (int m = 1; m <= 1000; ++m) {
        // Even step: m (b - m) x / ((a + 2m - 1)(a + 2m)); odd step: -(a + m)(a + b + m) x / ((a + 2m)(a + 2m + 1)).
        for (const double coefficient : {m * (b - m) * x / ((a + 2.0 * m - 1.0) * (a + 2.0 * m)),
                                         -(a + m) * (a + b + m) * x / ((a + 2.0 * m) * (a + 2.0 * m + 1.0))}) {
            d = 1.0 + coefficient * d;
            if (std::fabs(d) < tiny) d = tiny;
            c = 1.0 + coefficient / c;
            if (std::fabs(c) < tiny) c = tiny;
            d = 1.0 / d;
            f *= c * d;
            if (std::fabs(c * d - 1.0) < eps && coefficient < 0.0) return std::exp(log_front) * f / a;
        }
    }
    return std::exp(log_front) * f / a;
}

// P(|T| > t) for T ~ t(dof).
inline double student_t_two_sided_tail(double t, double dof) {
    if (!(dof < 1e7)) return std::erfc(t / std::sqrt(2.0));  // the normal limit
    return incomplete_beta(dof / (dof + t * t), 0.5 * dof, 0.5);
}

// The t with P(|T| > t) = p for T ~ t(dof), by bisection.
inline double student_t_two_sided_quantile(double p, double dof) {
    double lo = 0.0, hi = 1e3;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (student_t_two_sided_tail(mid, dof) > p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// Welch-Satterthwaite degrees of freedom of a difference of two means with standard errors se_a
// and se_b estimated from n_a and n_b samples.
inline double welch_dof(double se_a, double n_a, double se_b, double n_b) {
    const double va = se_a * se_a, vb = se_b * se_b;
    const double denominator = va * va / (n_a - 1.0) + vb * vb / (n_b - 1.0);
    return denominator > 0.0 ? (va + vb) * (va + vb) / denominator : std::numeric_limits<double>::infinity();
}

}  // namespace peensim
