// Exact shot-shot times of impact against closed forms: head-on, glancing and grazing passes under
// gravity, paths described from different reference times, and the state at the start (overlap,
// touching while approaching or separating).
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/sphere_pair_toi.h"

namespace peensim {
namespace {

const Vec3 kGravity(0, 0, -9.81);
constexpr double kR1 = 1e-3, kR2 = 0.5e-3;  // m
constexpr double kS = kR1 + kR2;

TEST(EventSpherePair, HeadOnUnderGravity) {
    // Both fall together; along x they close at 3 m/s from 10 mm apart.
    const Trajectory p1{Vec3(0, 0, 0.05), Vec3(1, 0, 0.4), kGravity, 0.0};
    const Trajectory p2{Vec3(0.01, 0, 0.05), Vec3(-2, 0, 0.4), kGravity, 0.0};
    PairContact contact;
    ASSERT_EQ(sphere_pair_toi(p1, kR1, p2, kR2, 0.0, 1.0, contact), ToiStatus::impact);
    const double t = (0.01 - kS) / 3.0;
    EXPECT_NEAR(contact.time, t, 1e-12 * t);
    EXPECT_NEAR((contact.normal - Vec3::UnitX()).norm(), 0.0, 1e-12);
    EXPECT_NEAR((p2.position(contact.time) - p1.position(contact.time)).norm(), kS, 1e-15);
    // Too short an interval, or one that starts after they met and separated... they only meet once.
    EXPECT_EQ(sphere_pair_toi(p1, kR1, p2, kR2, 0.0, 0.99 * t, contact), ToiStatus::miss);
}

TEST(EventSpherePair, GlancingAndGrazingPasses) {
    // Offset b across the line of approach: contact when the along-line gap is sqrt(S^2 - b^2).
    const double dx = 0.02, v = 1.7;
    for (double b : {0.0, 0.3 * kS, 0.9 * kS, 0.999 * kS}) {
        const Trajectory p1{Vec3(0, 0, 0), Vec3(v, 0, 0), kGravity, 0.0};
        const Trajectory p2{Vec3(dx, b, 0), Vec3::Zero(), kGravity, 0.0};
        PairContact contact;
        ASSERT_EQ(sphere_pair_toi(p1, kR1, p2, kR2, 0.0, 1.0, contact), ToiStatus::impact) << b;
        const double along = std::sqrt(kS * kS - b * b);
        const double t = (dx - along) / v;
        EXPECT_NEAR(contact.time, t, 1e-12 * t) << b;
        EXPECT_NEAR((contact.normal - Vec3(along, b, 0) / kS).norm(), 0.0, 1e-9) << b;
    }
    // b = S exactly: a tangent pass, reported as a touch when the centres are abreast.
    const Trajectory p1{Vec3(0, 0, 0), Vec3(v, 0, 0), kGravity, 0.0};
    const Trajectory graze{Vec3(dx, kS, 0), Vec3::Zero(), kGravity, 0.0};
    PairContact contact;
    ASSERT_EQ(sphere_pair_toi(p1, kR1, graze, kR2, 0.0, 1.0, contact), ToiStatus::impact);
    EXPECT_NEAR(contact.time, dx / v, 1e-12 * dx / v);
    EXPECT_NEAR((contact.normal - Vec3::UnitY()).norm(), 0.0, 1e-12);
    // A hair wider: no contact.
    const Trajectory wide{Vec3(dx, kS * (1 + 1e-9), 0), Vec3::Zero(), kGravity, 0.0};
    EXPECT_EQ(sphere_pair_toi(p1, kR1, wide, kR2, 0.0, 1.0, contact), ToiStatus::miss);
}

TEST(EventSpherePair, PathsMayReferToDifferentTimes) {
    // The second path is the same physical motion as in the head-on case, described from t0 = -0.3 s.
    const Trajectory p1{Vec3(0, 0, 0.05), Vec3(1, 0, 0.4), kGravity, 0.0};
    const Trajectory same{Vec3(0.01, 0, 0.05), Vec3(-2, 0, 0.4), kGravity, 0.0};
    const Trajectory p2{same.position(-0.3), same.velocity(-0.3), kGravity, -0.3};
    PairContact contact;
    ASSERT_EQ(sphere_pair_toi(p1, kR1, p2, kR2, 0.0, 1.0, contact), ToiStatus::impact);
    const double t = (0.01 - kS) / 3.0;
    EXPECT_NEAR(contact.time, t, 1e-12);
    // Starting the search later (t_begin = 1 ms) gives the same contact.
    ASSERT_EQ(sphere_pair_toi(p1, kR1, p2, kR2, 1e-3, 1.0, contact), ToiStatus::impact);
    EXPECT_NEAR(contact.time, t, 1e-12);
}

TEST(EventSpherePair, StateAtTheStart) {
    PairContact contact;
    // Overlapping by a third of the contact distance, whatever the motion.
    const Trajectory a{Vec3::Zero(), Vec3(1, 0, 0), kGravity, 0.0};
    const Trajectory deep{Vec3(kS * 0.66, 0, 0), Vec3(1, 0, 0), kGravity, 0.0};
    ASSERT_EQ(sphere_pair_toi(a, kR1, deep, kR2, 0.0, 1.0, contact), ToiStatus::overlapping);
    EXPECT_EQ(contact.time, 0.0);
    EXPECT_NEAR((contact.normal - Vec3::UnitX()).norm(), 0.0, 1e-15);
    // Touching (gap within the tolerance) after a bounce, separating: never again.
    for (double gap : {0.0, -1e-12 * kS, 1e-12 * kS}) {
        const Trajectory touching{Vec3(kS + gap, 0, 0), Vec3(2, 0.1, 0), kGravity, 0.0};
        EXPECT_EQ(sphere_pair_toi(a, kR1, touching, kR2, 0.0, 1.0, contact), ToiStatus::miss) << gap;
        // The same, approaching: an impact now.
        const Trajectory closing{Vec3(kS + gap, 0, 0), Vec3(0.5, 0.1, 0), kGravity, 0.0};
        ASSERT_EQ(sphere_pair_toi(a, kR1, closing, kR2, 0.0, 1.0, contact), ToiStatus::impact) << gap;
        EXPECT_NEAR(contact.time, 0.0, 1e-14);  // a positive gap closes in gap / 0.5 m/s
    }
    // Equal velocities: the gap never changes.
    const Trajectory parallel{Vec3(0.01, 0, 0), Vec3(1, 0, 0), kGravity, 0.0};
    EXPECT_EQ(sphere_pair_toi(a, kR1, parallel, kR2, 0.0, 1.0, contact), ToiStatus::miss);
}

}  // namespace
}  // namespace peensim
