// A shot's path seen from a turning part (engine/event/turning_frame_path.h): its Taylor parabola
// at u and the bound on how far the exact path strays from it, against the exact path computed
// from the part's closed-form pose at each time.
#include "engine/event/turning_frame_path.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace peensim::testing {
namespace {

constexpr double kRpm = 2.0 * M_PI / 60.0;  // rad/s per rpm

Vec3 random_unit(std::mt19937_64& rng) {
    std::normal_distribution<double> n(0.0, 1.0);
    return Vec3(n(rng), n(rng), n(rng)).normalized();
}

// A part turning at `rpm` about a random axis through a random point, set at a random rest pose.
Kinematics turning(double rpm, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> uni(-0.05, 0.05);
    Kinematics k;
    k.kind = Kinematics::Kind::rotating;
    k.rest.rotation = Eigen::AngleAxisd(1.3, random_unit(rng)).toRotationMatrix();
    k.rest.translation = Vec3(uni(rng), uni(rng), uni(rng));
    k.axis_point_m = Vec3(uni(rng), uni(rng), uni(rng));
    k.axis_direction = random_unit(rng);
    k.omega_rad_per_s = rpm * kRpm;
    return k;
}

// Over random flights, parts at 30-30000 rpm either way and stretches of 0.1-50 ms, the exact path
// in the part's frame never strays from the parabola by more than the bound, and the bound is not
// loose by more than the terms it adds up (the largest error seen is a fair share of it).
TEST(TurningFramePath, TheExactPathInThePartsFrameStaysWithinTheBoundOfItsParabola) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    const Vec3 g(0.0, 0.0, -9.81);
    double tightest = 0.0;  // the largest error seen over its bound
    for (int k = 0; k < 400; ++k) {
        const double rpm = (k % 2 == 0 ? 1.0 : -1.0) * 30.0 * std::pow(1000.0, uni(rng));
        const Kinematics kin = turning(rpm, rng);
        const SimTime epoch{1234.5 * uni(rng), 0.0};
        const Trajectory path{Vec3(0.1 * uni(rng), 0.1 * uni(rng), 0.1 * uni(rng)), 3.0 * uni(rng) * random_unit(rng), g, 0.0};
        const double u = 0.01 * uni(rng), span = 1e-4 * std::pow(500.0, uni(rng));
        const TurningFramePath local = turning_frame_path(kin, epoch, path, u, u + span);
        ASSERT_GT(local.jerk_bound, 0.0);
        EXPECT_NEAR(local.stretch_within(local.deviation(span)), span, 1e-12 * span);
        for (int j = 0; j <= 20; ++j) {
            const double tau = span * j / 20.0;
            const Vec3 exact = kin.pose(epoch, u + tau).to_component(path.position(u + tau));
            const double error = (exact - local.parabola.position(u + tau)).norm();
            const double rounding = 1e-14 * (1.0 + exact.norm());  // m, of the pose's and the parabola's sums
            EXPECT_LE(error, local.deviation(tau) + rounding) << "flight " << k << ", " << rpm << " rpm, tau " << tau << " s";
            if (local.deviation(tau) > 1e3 * rounding) tightest = std::max(tightest, error / local.deviation(tau));
        }
    }
    EXPECT_GT(tightest, 0.2);
}

// Where nothing turns the frame, the parabola is the path itself: position, velocity and
// acceleration at u, and no stray.
TEST(TurningFramePath, AtRestThePartsFrameSeesTheFlightsOwnParabolaMovedIntoIt) {
    std::mt19937_64 rng(3);
    Kinematics kin = turning(0.0, rng);
    const Trajectory path{Vec3(0.01, 0.02, 0.03), Vec3(1.0, -0.5, 2.0), Vec3(0.0, 0.0, -9.81), 0.0};
    const TurningFramePath local = turning_frame_path(kin, SimTime{}, path, 0.004, 0.02);
    EXPECT_EQ(local.jerk_bound, 0.0);
    EXPECT_EQ(local.deviation(0.01), 0.0);
    EXPECT_TRUE(std::isinf(local.stretch_within(1e-9)));
    for (const double t : {0.004, 0.01, 0.02}) {
        const Vec3 exact = kin.rest.to_component(path.position(t));
        EXPECT_LT((local.parabola.position(t) - exact).norm(), 1e-15) << t;
    }
}

}  // namespace
}  // namespace peensim::testing
