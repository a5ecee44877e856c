#include "analysis/avrami.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace peensim {

namespace {

// Gauss-Newton iterations of the refinement; it converges in a handful from the log-linear start.
constexpr int kRefinementIterations = 50;
// Relative change of k (-) below which the refinement stops.
constexpr double kRefinementTolerance = 1e-12;

}  // namespace

AvramiFit fit_avrami(const std::vector<CoveragePoint>& points) {
    double sum_wty = 0.0, sum_wtt = 0.0;  // s, s^2 (weighted)
    int informative = 0;
    for (const CoveragePoint& p : points) {
        if (!(p.time_s > 0.0) || !(p.coverage < 1.0)) continue;
        const double c = std::max(p.coverage, 0.0);
        const double w = (1.0 - c) * (1.0 - c);
        sum_wty += w * p.time_s * -std::log1p(-c);
        sum_wtt += w * p.time_s * p.time_s;
        if (c > 0.0) ++informative;
    }
    if (informative == 0 || !(sum_wty > 0.0)) throw std::invalid_argument("fit_avrami: need a point with t > 0 and 0 < coverage < 1");
    double k = sum_wty / sum_wtt;

    double last_time = 0.0;
    int used = 0;
    for (const CoveragePoint& p : points)
        if (p.time_s > 0.0) {
            ++used;
            last_time = std::max(last_time, p.time_s);
        }

    double sum_jj = 0.0, sum_rr = 0.0;
    for (int iteration = 0; iteration < kRefinementIterations; ++iteration) {
        double sum_jr = 0.0;
        sum_jj = 0.0;
        for (const CoveragePoint& p : points) {
            if (!(p.time_s > 0.0)) continue;
            const double e = std::exp(-k * p.time_s);
            const double residual = p.coverage - (1.0 - e);
            const double jacobian = p.time_s * e;  // dC/dk (s)
            sum_jr += jacobian * residual;
            sum_jj += jacobian * jacobian;
        }
        if (!(sum_jj > 0.0)) break;
        double step = sum_jr / sum_jj;
        if (k + step <= 0.0) step = -0.5 * k;  // keep k positive
        k += step;
        if (std::abs(step) <= kRefinementTolerance * k) break;
    }
    sum_jj = 0.0;
    for (const CoveragePoint& p : points) {
        if (!(p.time_s > 0.0)) continue;
        const double e = std::exp(-k * p.time_s);
        const double residual = p.coverage - (1.0 - e);
        sum_rr += residual * residual;
        sum_jj += (p.time_s * e) * (p.time_s * e);
    }

    AvramiFit fit;
    fit.k_per_s = k;
    fit.k_standard_error_per_s = (used > 1 && sum_jj > 0.0) ? std::sqrt(sum_rr / (used - 1) / sum_jj) : 0.0;
    fit.time_to_98_percent_s = std::log(50.0) / k;
    fit.extrapolated = fit.time_to_98_percent_s > last_time;
    fit.points_used = used;
    return fit;
}

}  // namespace peensim
