// Fitting a measured Almen saturation curve (arc height against exposure) and finding its SAE J443
// saturation point. Pure computation in the caller's units: exposure in any unit (s, min, passes),
// arc height in any unit; the results come in the same units.
//
// The two forms of the curve-fitting practice that grew around SAE J443 (D. Kirk's "Solver" suite of
// programs, The Shot Peener 2019 "The Solver Story" and 2024 "Estimating Peening Intensity": exponential
// equations with 2, 3 or 4 parameters, each fitting closer; SAE J2597 "Computer Generated Shot
// Peening Saturation Curves" validates any such algorithm on ten data sets to +-0.001 in):
//   2P: h(t) = a (1 - exp(-b t))
//   3P: h(t) = a (1 - exp(-b t^c))    (2P is 3P with c = 1)
// The saturation point T (J443): doubling the exposure raises the arc height by 10 %,
// h(2T) = 1.1 h(T); the intensity is h(T). With x = exp(-b T^c) and k = 2^c,
// h(2T) / h(T) = (1 - x^k) / (1 - x): for 2P (k = 2) this is 1 + x, so x = 0.1, T = ln(10) / b and
// h(T) = 0.9 a exactly; for 3P it is solved for y = b T^c (a unique root when k > 1.1, i.e.
// c > log2(1.1) = 0.1375; a flatter curve never rises by 10 % on doubling, so it has no T).
//
// Least squares: the arc height enters linearly (a), so each fit starts from a grid over the
// remaining parameters with a solved for exactly (variable projection), then Levenberg-Marquardt
// on all of them; with exact data it converges to the data's parameters to rounding.
#pragma once

#include <array>
#include <span>
#include <string>

namespace peensim {

struct SaturationDatum {
    double exposure = 0.0;    // the curve's exposure unit (>= 0)
    double arc_height = 0.0;  // the curve's height unit
};

enum class SaturationForm { two_parameter, three_parameter };
const char* saturation_form_name(SaturationForm form);  // "2P", "3P"

// h = a (1 - exp(-b t^c)).
struct SaturationCurve {
    double a = 0.0;  // height unit: the arc height the curve tends to
    double b = 0.0;  // exposure unit^-c
    double c = 1.0;  // -, the shape (1: the 2P form)
    double arc_height(double exposure) const;
};

// The J443 saturation point of a curve.
struct SaturationPoint {
    bool exists = false;     // false when c <= log2(1.1) (or a, b not positive)
    double time = 0.0;       // exposure unit, T: h(2T) = 1.1 h(T)
    double intensity = 0.0;  // height unit, h(T)
};
SaturationPoint saturation_point(const SaturationCurve& curve);

// The J443 rise on doubling the exposure.
inline constexpr double kSaturationRise = 1.1;

struct SaturationFit {
    SaturationForm form = SaturationForm::two_parameter;
    bool fitted = false;                   // false: `problem` says why (too few points, no saturation in the data)
    std::string problem;                   // why the fit is missing or not to be trusted ("" if fine)
    SaturationCurve curve;                 // the fitted parameters
    int points = 0;                        // data points used
    int parameters = 2;                    // 2 or 3
    double residual_sum_of_squares = 0.0;  // height unit^2
    double rms_residual = 0.0;             // height unit, sqrt(SSR / points)
    double residual_sd = 0.0;              // height unit, sqrt(SSR / (points - parameters)); NaN when no degree of freedom is left
    SaturationPoint point;                 // its J443 saturation point
    // Standard errors of the saturation time and intensity from the fit's covariance
    // (s^2 (J^T J)^-1, delta method); NaN when no degree of freedom is left.
    double time_standard_error = 0.0;       // exposure unit
    double intensity_standard_error = 0.0;  // height unit
};

// Fits the 2P or 3P form to the points (any order, replicates allowed). 2P needs at least 2
// distinct exposures > 0, 3P at least 3; otherwise `fitted` is false with the reason (also for
// arc heights that fall with exposure). The cost grows with the distinct exposures (replicates are
// merged exactly): 10^5 distinct ones take ~0.5 s.
SaturationFit fit_saturation_curve(std::span<const SaturationDatum> data, SaturationForm form);

// Arc heights that fall with exposure are no saturation curve (it rises, then levels off): the
// mean of the strips at the longest exposure lies below the mean of those at the shortest exposure
// > 0 by more than kFallingShare of the highest arc height. Gauge noise on strips at the plateau
// is ~1 % of it, so a fall of 10 % is not noise but swapped columns or mislabelled rows.
inline constexpr double kFallingShare = 0.1;
struct ArcHeightFall {
    bool falls = false;
    double shortest_exposure = 0.0, longest_exposure = 0.0;  // the curve's exposure unit
    double shortest_height = 0.0, longest_height = 0.0;      // height unit: the strips' mean there
};
ArcHeightFall arc_height_fall(std::span<const SaturationDatum> data);

// Which fit to use: the 2P unless the 3P's extra parameter lowers the residual significantly:
// an F-test of the nested models at 95 % (F = (SSR2 - SSR3) / (SSR3 / (n - 3)), one numerator
// degree of freedom), which needs n >= 5 points (two degrees of freedom left to judge by). A fit
// without a saturation point is not chosen. `reason` says why, in a sentence.
struct SaturationChoice {
    SaturationForm form = SaturationForm::two_parameter;
    bool any = false;  // false: neither fit has a saturation point
    std::string reason;
};
SaturationChoice choose_saturation_fit(const SaturationFit& two, const SaturationFit& three);

}  // namespace peensim
