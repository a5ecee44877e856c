// The predictive Almen model (analysis/almen_model.h) on synthetic impacts whose answer is known in
// closed form: one speed, a doubled speed, a doubled shot, a doubled flow, a mix of two speeds, the
// start of a run left out, and the calibration round trip.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/almen_model.h"
#include "contact/dent.h"
#include "support/test_meshes.h"

namespace peensim {
namespace {

constexpr double kDensity = 7800.0;  // kg/m3, steel shot
constexpr double kYield = 1.3e9;     // Pa, the strip
constexpr double kFace = 4e-4;       // m2, the square strip's face

// A steady stream on the face: `per_second` impacts per second for `seconds` s, sampled every
// second, each impact of shot diameter D at normal speed v (alternating through `speeds`).
std::vector<AlmenDosePoint> stream(double D, const std::vector<double>& speeds, int per_second, int seconds, double burst_speed = 0.0) {
    const TriangleMesh strip = peensim::testing::square(0.02);
    const double mass = kDensity * M_PI * D * D * D / 6.0;
    AlmenDose dose(strip, Vec3(0, 0, 1), mass);
    std::vector<AlmenDosePoint> curve{dose.point_at(0.0)};
    std::size_t k = 0;
    for (int s = 1; s <= seconds; ++s) {
        for (int i = 0; i < per_second; ++i) {
            // A first second of faster impacts (the shot's first launch off a sonotrode), when asked.
            const double v = (s == 1 && burst_speed > 0.0) ? burst_speed : speeds[k++ % speeds.size()];
            EXPECT_TRUE(dose.add(i % 2, v));
            dose.add_dent(dent_diameter(D, kDensity, v, kYield));
        }
        curve.push_back(dose.point_at(s));
    }
    return curve;
}

double rel(double got, double want) { return std::fabs(got - want) / std::fabs(want); }

TEST(AlmenModel, OneSpeedGivesItsDentAndTheExactCoveringRate) {
    const double D = 2e-3, v = 4.0;
    const AlmenExposure e = almen_exposure(stream(D, {v}, 500, 10));
    const double phi = dent_diameter(D, kDensity, v, kYield);
    EXPECT_LT(rel(e.dent_size_m, phi), 1e-12);
    EXPECT_LT(rel(e.covering_rate_per_s, 500.0 * 0.25 * M_PI * phi * phi / kFace), 1e-12);
}

TEST(AlmenModel, TwoSpeedsWeighTheDentsByTheirArea) {
    const double D = 1e-3, v1 = 2.0, v2 = 8.0;
    const double p1 = dent_diameter(D, kDensity, v1, kYield), p2 = dent_diameter(D, kDensity, v2, kYield);
    const AlmenExposure e = almen_exposure(stream(D, {v1, v2}, 400, 6));
    EXPECT_LT(rel(e.dent_size_m, (p1 * p1 * p1 + p2 * p2 * p2) / (p1 * p1 + p2 * p2)), 1e-12);
}

TEST(AlmenModel, TheStartOfARunIsLeftOut) {
    // Faster impacts in the first second do not move the steady dent size or covering rate.
    const AlmenExposure steady = almen_exposure(stream(2e-3, {3.0}, 300, 10));
    const AlmenExposure burst = almen_exposure(stream(2e-3, {3.0}, 300, 10, 9.0));
    EXPECT_LT(rel(burst.dent_size_m, steady.dent_size_m), 1e-12);
    EXPECT_LT(rel(burst.covering_rate_per_s, steady.covering_rate_per_s), 1e-12);
}

// The measured curve of the calibration: 2P, a = 0.25 mm, b = 0.4 /min.
AlmenModelCalibration calibrated_on(const AlmenExposure& run, double c = 1.0) {
    return almen_calibration(SaturationCurve{0.25e-3, 0.4, c}, 60.0, run, "A");
}

TEST(AlmenModel, CalibratingOnARunAndPredictingItGivesTheMeasuredCurveBack) {
    for (const double c : {1.0, 1.7}) {
        const AlmenExposure run = almen_exposure(stream(2e-3, {3.0, 5.0}, 300, 10));
        const AlmenModelCalibration cal = calibrated_on(run, c);
        const AlmenPrediction p = predict_almen(cal, run);
        EXPECT_EQ(p.intensity_ratio, 1.0);
        EXPECT_EQ(p.time_ratio, 1.0);
        EXPECT_EQ(p.curve.a, 0.25e-3);
        EXPECT_EQ(p.curve.c, c);
        const SaturationPoint measured = saturation_point(SaturationCurve{0.25e-3, 0.4, c});  // in min
        EXPECT_LT(rel(p.point.time, 60.0 * measured.time), 1e-14);
        EXPECT_LT(rel(p.point.intensity, measured.intensity), 1e-14);
        // The arc height after t s of this run's steady covering is the measured curve's at t.
        for (const double t_s : {30.0, 90.0, 400.0}) {
            const double h = predicted_arc_height(cal, run, run.covering_rate_per_s * t_s);
            EXPECT_LT(rel(h, SaturationCurve{0.25e-3, 0.4, c}.arc_height(t_s / 60.0)), 1e-13) << t_s;
        }
        EXPECT_LT(rel(cal.time_constant_s(), 60.0 * std::pow(0.4, -1.0 / c)), 1e-14);
    }
}

TEST(AlmenModel, DoubledSpeedDoubledShotDoubledFlow) {
    const double D = 2e-3, v = 3.0;
    const AlmenExposure base = almen_exposure(stream(D, {v}, 300, 10));
    const AlmenModelCalibration cal = calibrated_on(base);
    const SaturationPoint at_base = predict_almen(cal, base).point;
    // Every impact twice as fast: dents x sqrt(2) (eq. 10: phi ~ v^(1/2)), so intensity x sqrt(2);
    // each dent covers twice the area, so the saturation time halves.
    const AlmenPrediction fast = predict_almen(cal, almen_exposure(stream(D, {2.0 * v}, 300, 10)));
    EXPECT_LT(rel(fast.intensity_ratio, std::sqrt(2.0)), 1e-12);
    EXPECT_LT(rel(fast.point.intensity, std::sqrt(2.0) * at_base.intensity), 1e-12);
    EXPECT_LT(rel(fast.point.time, 0.5 * at_base.time), 1e-12);
    // Shot of twice the diameter at the same speed: dents x 2, area per dent x 4.
    const AlmenPrediction big = predict_almen(cal, almen_exposure(stream(2.0 * D, {v}, 300, 10)));
    EXPECT_LT(rel(big.point.intensity, 2.0 * at_base.intensity), 1e-12);
    EXPECT_LT(rel(big.point.time, 0.25 * at_base.time), 1e-12);
    // Twice the impacts per second (the flow), same shot and speed: the intensity stays, the time halves.
    const AlmenPrediction flow = predict_almen(cal, almen_exposure(stream(D, {v}, 600, 10)));
    EXPECT_LT(rel(flow.point.intensity, at_base.intensity), 1e-12);
    EXPECT_LT(rel(flow.point.time, 0.5 * at_base.time), 1e-12);
    // The shape c of a 3P calibration carries over: the same ratios.
    const AlmenModelCalibration cal3 = calibrated_on(base, 1.7);
    const AlmenPrediction fast3 = predict_almen(cal3, almen_exposure(stream(D, {2.0 * v}, 300, 10)));
    EXPECT_LT(rel(fast3.point.time, 0.5 * predict_almen(cal3, base).point.time), 1e-12);
}

TEST(AlmenModel, NoDentsNoExposure) {
    const TriangleMesh strip = peensim::testing::square(0.02);
    AlmenDose dose(strip, Vec3(0, 0, 1), 1e-5);
    EXPECT_TRUE(dose.add(0, 3.0));  // a dose but no yield stress: no dent
    EXPECT_FALSE(dose.add(-1, 3.0));
    const std::vector<AlmenDosePoint> curve{dose.point_at(0.0), dose.point_at(1.0)};
    EXPECT_FALSE(almen_exposure(curve).valid());
}

}  // namespace
}  // namespace peensim
