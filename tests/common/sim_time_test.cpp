// Simulated time and sonotrode phase stay exact over long runs (engineering standard: 60 s runs).
#include <gtest/gtest.h>

#include <cmath>

#include "common/sim_time.h"
#include "model/kinematics.h"

using peensim::SimTime;

TEST(SimTime, TwoMillionStepsOfSixtySecondsStayExact) {
    // Steps of a dyadic size are exactly representable, so the exact sum is known; a plain double
    // sum of them would still be exact, so irregular steps are used too (checked against long double).
    SimTime t;
    long double exact = 0.0L;
    double plain = 0.0;
    for (int k = 0; k < 2'000'000; ++k) {
        const double dt = 3.0e-5 * (1.0 + 0.37 * std::sin(0.001 * k));  // s, ~20-40 us like eq. 7 steps
        t.advance(dt);
        exact += static_cast<long double>(dt);
        plain += dt;
    }
    const double error = std::abs(static_cast<double>(static_cast<long double>(t.hi) + static_cast<long double>(t.lo) - exact));
    const double plain_error = std::abs(static_cast<double>(static_cast<long double>(plain) - exact));
    std::cout << "[ sim time ] after " << t.seconds() << " s: compensated error " << error << " s, plain double sum error " << plain_error
              << " s\n";
    EXPECT_GT(t.seconds(), 55.0);
    EXPECT_LT(error, 1e-14);  // s: ~ an ulp of 60 s; long double carries ~1e-19 relative
}

TEST(SimTime, CycleFractionIsExactAtSixtySeconds) {
    // 20 kHz, t = 60 s + 12.5 us: a quarter period past a whole number of cycles.
    SimTime t;
    t.advance(60.0);
    t.advance(12.5e-6);
    EXPECT_NEAR(t.cycle_fraction(20000.0), 0.25, 1e-9);
    // With an offset within a step.
    EXPECT_NEAR(t.cycle_fraction(20000.0, 25e-6), 0.75, 1e-9);
}

TEST(Kinematics, VibratingSonotrodePoseAndVelocityInClosedForm) {
    peensim::Kinematics k;
    k.kind = peensim::Kinematics::Kind::vibrating;
    k.axis = peensim::Vec3::UnitZ();
    k.amplitude_m = 25e-6;
    k.frequency_hz = 20000.0;
    SimTime t;
    t.advance(60.0);
    t.advance(12.5e-6);  // sin = 1: at the top, at rest
    EXPECT_NEAR(k.pose(t).translation.z(), 25e-6, 1e-15);
    EXPECT_NEAR(k.point_velocity(peensim::Vec3::Zero(), t).z(), 0.0, 1e-10);  // m/s: phase exact to ~1e-11 rad
    EXPECT_NEAR(k.point_acceleration(peensim::Vec3::Zero(), t).z(), -25e-6 * std::pow(2.0 * M_PI * 20000.0, 2), 1e-3);
    // Quarter period later: through the middle, moving down at the peak speed 2 pi F A0.
    EXPECT_NEAR(k.pose(t, 12.5e-6).translation.z(), 0.0, 1e-16);
    EXPECT_NEAR(k.point_velocity(peensim::Vec3::Zero(), t, 12.5e-6).z(), -2.0 * M_PI * 20000.0 * 25e-6, 1e-9);
}

TEST(Kinematics, RotatingPartPoseAndSurfaceVelocity) {
    peensim::Kinematics k;
    k.kind = peensim::Kinematics::Kind::rotating;
    k.axis_point_m = peensim::Vec3(0.0, 0.0, 0.04);
    k.axis_direction = peensim::Vec3::UnitY();
    k.omega_rad_per_s = 2.0 * M_PI;  // 60 rpm
    SimTime t;
    t.advance(0.25);                                                            // a quarter turn about +y: +z goes to +x
    const peensim::Vec3 p = k.pose(t).to_world(peensim::Vec3(0.0, 0.0, 0.05));  // 10 mm above the axis at rest
    EXPECT_NEAR(p.x(), 0.01, 1e-15);
    EXPECT_NEAR(p.z(), 0.04, 1e-15);
    const peensim::Vec3 v = k.point_velocity(p, t);  // omega x r = 2 pi * (y x x) * 0.01 = -2 pi 0.01 z
    EXPECT_NEAR(v.z(), -2.0 * M_PI * 0.01, 1e-15);
    EXPECT_NEAR(k.peak_surface_speed(0.02), 2.0 * M_PI * 0.02, 1e-15);
}
