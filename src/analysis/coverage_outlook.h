// Where coverage is heading: from a coverage curve C(t) and the dent area delivered in each time
// batch, the Avrami rate k (C = 1 - exp(-k t)) with a 95 % interval, the time to 98 % ("full"
// coverage, SAE J2277) with its interval, and how far that lies beyond the analysed time.
//
// The interval. The fit's own standard error (avrami.h) comes from the residuals of a cumulative
// curve, whose errors are correlated: it understates the uncertainty. Independently, with dents at
// random -ln(1 - C) = (dent area delivered) / area, so k is proportional to the rate of dent area
// delivered, whose scatter between the run's time batches (batch means) measures how well one run
// knows it (bursts, a part that turns, few impacts). The relative standard error of k is the larger
// of the two, and its 95 % interval k (1 +- t(0.975, batches - 1) se_rel); the time to 98 % is
// ln(50) / k, its interval ln(50) / k_high .. ln(50) / k_low (unbounded when k_low <= 0).
// Pure computation: no file I/O, no printing.
#pragma once

#include <span>
#include <vector>

#include "analysis/avrami.h"

namespace peensim {

struct CoverageOutlook {
    double coverage = 0.0;           // 0..1, the curve's last value
    bool fitted = false;             // false: no usable point (no impact yet, or already 1)
    double k_per_s = 0.0;            // 1/s (NaN unless fitted)
    double k_relative_se = 0.0;      // -, the larger of the fit's and the batches'
    double k_low_per_s = 0.0;        // 1/s, 95 % interval (>= 0)
    double k_high_per_s = 0.0;       // 1/s
    double time_to_98_s = 0.0;       // s, ln(50) / k
    double time_to_98_low_s = 0.0;   // s, ln(50) / k_high
    double time_to_98_high_s = 0.0;  // s, ln(50) / k_low (infinity when k_low is 0)
    double run_multiple = 0.0;       // -, time_to_98 / the curve's last time: > 1 is extrapolated
};

// curve: coverage against the time since the analysis window opened (s); batch_dent_area: the dent
// area (m2, any common factor) delivered in each of equal time batches of that window. With no
// usable batch (fewer than 2, or none delivered anything) only the fit's error counts.
CoverageOutlook coverage_outlook(const std::vector<CoveragePoint>& curve, std::span<const double> batch_dent_area);

}  // namespace peensim
