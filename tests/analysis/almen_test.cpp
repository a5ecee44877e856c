// The Almen strip: only its peened face counts, the dose is the normal kinetic energy per area
// exactly, the steady rate ignores the start of a run, and the calibrated saturation point obeys
// the SAE J443 rule h(2T) = 1.1 h(T) with intensity 0.9 a.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/almen.h"
#include "geometry/box_mesh.h"
#include "support/test_meshes.h"

using namespace peensim;

TEST(Almen, DoseCountsTheFaceOnlyAndIsHalfMVSquaredPerArea) {
    const TriangleMesh strip = peensim::testing::square(0.02);  // 2 triangles facing +z, 4e-4 m2
    const double mass = 3.2e-5;                                 // kg
    AlmenDose dose(strip, Vec3(0, 0, 1), mass);
    EXPECT_DOUBLE_EQ(dose.face_area_m2(), 4e-4);
    dose.add(0, 2.0);
    dose.add(1, 4.0);
    dose.add(-1, 9.0);  // a facet the mesh lacks
    dose.add(7, 9.0);   // out of range
    EXPECT_EQ(dose.face_impacts(), 2u);
    EXPECT_DOUBLE_EQ(dose.dose_J_per_m2(), 0.5 * mass * (4.0 + 16.0) / 4e-4);
    EXPECT_DOUBLE_EQ(dose.mean_normal_speed(), 3.0);
    // Facing the other way there is no face: a clear error, not a zero dose.
    EXPECT_THROW(AlmenDose(strip, Vec3(0, 0, -1), mass), std::invalid_argument);
}

TEST(Almen, OnAStripBoxOnlyThePeenedFaceCounts) {
    BoxSpec spec;
    spec.size_m = Vec3(76.2e-3, 19e-3, 1.29e-3);
    const TriangleMesh strip = box(spec);
    AlmenDose dose(strip, Vec3(0, 0, 1), 1.0);
    EXPECT_NEAR(dose.face_area_m2(), 76.2e-3 * 19e-3, 1e-15);
    int counted = 0;
    for (std::size_t t = 0; t < strip.triangle_count(); ++t) {
        const std::uint64_t before = dose.face_impacts();
        dose.add(static_cast<int>(t), 1.0);
        counted += dose.face_impacts() > before;
    }
    EXPECT_EQ(counted, 2);  // the two triangles of the top face; sides and back do not count
}

TEST(Almen, SteadyRateIgnoresTheStartOfTheRun) {
    // A burst of 50 J/m2 in the first 0.1 s, then 10 J/(m2 s).
    std::vector<AlmenDosePoint> curve{{0.0, 0.0}};
    for (int i = 1; i <= 50; ++i) {
        const double t = 0.1 * i;
        curve.push_back({t, 50.0 + 10.0 * (t - 0.1)});
    }
    EXPECT_NEAR(almen_dose_rate(curve), 10.0, 1e-9);
    EXPECT_EQ(almen_dose_rate({{0.0, 0.0}}), 0.0);
    EXPECT_DOUBLE_EQ(almen_dose_rate({{0.0, 0.0}, {2.0, 6.0}}), 3.0);
}

TEST(Almen, SaturationObeysTheJ443Rule) {
    const AlmenCalibration cal{0.3e-3, 400.0};           // a = 0.3 mm, E_c = 400 J/m2
    const double rate = 25.0;                            // J/(m2 s)
    const auto sat = almen_saturation(rate, cal, 80.0);  // T = 36.8 s: 2T within 80 s
    ASSERT_TRUE(sat.has_value());
    EXPECT_DOUBLE_EQ(sat->rate_constant_per_s, rate / 400.0);
    EXPECT_NEAR(sat->saturation_time_s, std::log(10.0) * 400.0 / rate, 1e-12);
    const double h_T = almen_arc_height(rate * sat->saturation_time_s, cal);
    const double h_2T = almen_arc_height(2.0 * rate * sat->saturation_time_s, cal);
    EXPECT_NEAR(h_2T / h_T, 1.1, 1e-12);
    EXPECT_NEAR(h_T, sat->intensity_m, 1e-15);
    EXPECT_DOUBLE_EQ(sat->intensity_m, 0.9 * 0.3e-3);
    EXPECT_FALSE(sat->extrapolated);
}

TEST(Almen, SaturationBeyondTheRunIsFlaggedAndNoRateGivesNone) {
    const AlmenCalibration cal{0.3e-3, 400.0};
    EXPECT_TRUE(almen_saturation(25.0, cal, 5.0)->extrapolated);
    EXPECT_FALSE(almen_saturation(0.0, cal, 5.0).has_value());
    EXPECT_DOUBLE_EQ(almen_arc_height(0.0, cal), 0.0);
    EXPECT_NEAR(almen_arc_height(400.0, cal), 0.3e-3 * (1.0 - std::exp(-1.0)), 1e-18);
}
