// Predicting an Almen strip's saturation curve from a run's impacts on its peened face, calibrated on
// ONE measured curve and the run that reproduced its conditions. Pure computation.
//
// Why not the dose alone (analysis/almen.h)? Peening intensity is a shot stream's "depth-inducing
// capability", not its energy: a higher flow rate shortens the saturation time but does not raise
// the intensity, while bigger or faster shot do (D. Kirk, The Shot Peener: "Meaning, Measurement
// Philosophy and Verification of Peening Intensity", 2010; "Peening Intensity True Meaning and
// Measurement Strategy", 2016; "Prediction and Control of Indent Diameter", 2004: the larger the
// indent, the greater the intensity). Experiments agree: intensity rises with shot size, velocity and
// hardness, and indent size is about proportional to shot diameter (Tetsu-to-Hagane 41 (1955) 1093);
// the same intensity comes from small fast shot or large slow shot (Miao, Larose, Perron, Levesque,
// Surf. Coat. Technol. 205 (2010) 2055). The model:
//
// 1. Saturated arc height. The strip bends because a surface layer is plastically stretched; at
//    saturation the layer covers the face and its depth sets the arc height. The plastic zone under
//    a spherical dent reaches about one contact radius deep (Johnson's expanding-cavity picture,
//    the same estimate that gives eq. 10), so the layer's depth scales with the dent size, and
//        a = K delta,   delta = sum phi_i^3 / sum phi_i^2
//    the dent-area-weighted mean dent diameter over the face's impacts (each dent counts for the
//    share of the face it covers), phi_i = D_i (8 rho v_i^2 / (9 sigma_y))^(1/4) (eq. 10, the
//    impact's own shot size D_i and normal speed v_i, the strip's yield stress).
// 2. Approach to saturation. The layer spreads as dents cover the face: the curve follows the dent
//    area ratio A_r(t) = sum pi phi_i^2 / 4 / S (coverage = 1 - exp(-A_r), SAE J2277), which grows
//    at the steady covering rate k = dA_r/dt:
//        h(t) = a (1 - exp(-(A_r(t) / A_c)^c)),   with A_r = k t:   h = a (1 - exp(-(t / tau)^c)), tau = A_c / k
//    the form of the fitted measured curve (2P: c = 1; 3P: b = tau^-c).
// 3. Calibration on one measured curve (a_m, tau_m, c) and the run that reproduced it (delta_m, k_m):
//    K = a_m / delta_m, A_c = k_m tau_m. For any other run (delta, k):
//        a = a_m delta / delta_m,   tau = tau_m k_m / k,   the same c,
//    so the J443 intensity scales as delta / delta_m and the saturation time as k_m / k. Calibrating
//    on a run and predicting that run gives back the measured curve exactly.
// Consequences at a steady impact rate: normal speeds x s give intensity x sqrt(s) and saturation
// time / s; shot diameter x s (same speeds and impact rate) gives intensity x s and time / s^2; the
// impact rate x s leaves the intensity and divides the time by s. The strip's yield stress cancels
// between calibration and prediction when it is the same in both.
#pragma once

#include <string>
#include <vector>

#include "analysis/almen.h"
#include "analysis/saturation_fit.h"

namespace peensim {

// What a run's impacts do to the strip's face at their steady rate (the run's second half, as the
// dose rate, so the shot's first launch off the sonotrode does not bias it).
struct AlmenExposure {
    double dent_size_m = 0.0;          // m, delta: dent-area-weighted mean dent diameter
    double covering_rate_per_s = 0.0;  // 1/s, k: dent area ratio per second
    bool valid() const { return dent_size_m > 0.0 && covering_rate_per_s > 0.0; }
};

// From a strip's sampled curve (analysis/almen.h): k = the steady slope of the dent area ratio,
// delta = its size-weighted increase over the steady part / its increase (over the whole run when
// the steady part has no dent). Not valid (zeros) without dents.
AlmenExposure almen_exposure(const std::vector<AlmenDosePoint>& curve);

// What a scene carries: the measured curve's fit and the calibration run's exposure.
struct AlmenModelCalibration {
    SaturationCurve measured;  // h = a (1 - exp(-b t^c)): a in m, t in s
    AlmenExposure run;         // the run that reproduced the measured conditions
    std::string strip;         // "A", "N", "C", or "" (not given)
    // tau = b^(-1/c), s: the measured curve's time constant.
    double time_constant_s() const;
    double arc_height_per_dent_size() const { return measured.a / run.dent_size_m; }                 // -, K
    double dent_area_ratio_constant() const { return run.covering_rate_per_s * time_constant_s(); }  // -, A_c
};

// The measured curve as `calibration` from a fitted curve (exposure unit s_per_unit seconds,
// height in m) and a run: b is converted to seconds.
AlmenModelCalibration almen_calibration(const SaturationCurve& fitted, double seconds_per_exposure_unit, const AlmenExposure& run,
                                        const std::string& strip);

struct AlmenPrediction {
    SaturationCurve curve;         // a in m, b in s^-c, c
    SaturationPoint point;         // T in s, intensity in m
    double intensity_ratio = 0.0;  // -, delta / delta_m (the intensity against the calibration run's)
    double time_ratio = 0.0;       // -, k_m / k (the saturation time against the calibration run's)
};

// The saturation curve the model predicts for a run of exposure `run` (valid: see almen_exposure).
AlmenPrediction predict_almen(const AlmenModelCalibration& calibration, const AlmenExposure& run);

// The predicted arc height (m) once the face has received a dent area ratio A_r with dents of
// mean size run.dent_size_m: a (1 - exp(-(A_r / A_c)^c)).
double predicted_arc_height(const AlmenModelCalibration& calibration, const AlmenExposure& run, double dent_area_ratio);

}  // namespace peensim
