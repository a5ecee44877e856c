#include "analysis/almen_model.h"

#include <cmath>

namespace peensim {

AlmenExposure almen_exposure(const std::vector<AlmenDosePoint>& curve) {
    AlmenExposure e;
    if (curve.empty() || !(curve.back().dent_area_ratio > 0.0)) return e;
    e.covering_rate_per_s = almen_steady_slope(curve, &AlmenDosePoint::dent_area_ratio);
    const AlmenDosePoint& end = curve.back();
    const std::size_t start = almen_steady_start(curve);
    const AlmenDosePoint from = start < curve.size() ? curve[start] : AlmenDosePoint{};
    const double area = end.dent_area_ratio - from.dent_area_ratio;
    e.dent_size_m =
        area > 0.0 ? (end.dent_size_area_ratio_m - from.dent_size_area_ratio_m) / area : end.dent_size_area_ratio_m / end.dent_area_ratio;
    return e;
}

double AlmenModelCalibration::time_constant_s() const { return std::pow(measured.b, -1.0 / measured.c); }

AlmenModelCalibration almen_calibration(const SaturationCurve& fitted, double seconds_per_unit, const AlmenExposure& run,
                                        const std::string& strip) {
    AlmenModelCalibration c;
    c.measured = fitted;
    // b t^c with t in the curve's unit = b (t_s / s_per_unit)^c: b_s = b / s_per_unit^c.
    c.measured.b = fitted.b / std::pow(seconds_per_unit, fitted.c);
    c.run = run;
    c.strip = strip;
    return c;
}

AlmenPrediction predict_almen(const AlmenModelCalibration& cal, const AlmenExposure& run) {
    AlmenPrediction p;
    p.intensity_ratio = run.dent_size_m / cal.run.dent_size_m;
    p.time_ratio = cal.run.covering_rate_per_s / run.covering_rate_per_s;
    p.curve.c = cal.measured.c;
    p.curve.a = cal.measured.a * p.intensity_ratio;
    // tau = tau_m k_m / k: b = tau^-c = b_m (k / k_m)^c.
    p.curve.b = cal.measured.b * std::pow(1.0 / p.time_ratio, cal.measured.c);
    p.point = saturation_point(p.curve);
    return p;
}

double predicted_arc_height(const AlmenModelCalibration& cal, const AlmenExposure& run, double dent_area_ratio) {
    if (!(dent_area_ratio > 0.0)) return 0.0;
    const double a = cal.measured.a * run.dent_size_m / cal.run.dent_size_m;
    return a * -std::expm1(-std::pow(dent_area_ratio / cal.dent_area_ratio_constant(), cal.measured.c));
}

}  // namespace peensim
