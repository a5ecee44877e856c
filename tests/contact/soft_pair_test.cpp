// A soft contact's memory is its law's per-contact state (contact/soft_pair.h): the tangential
// spring lives in the state the law declares and the engine keeps without reading it. The law
// extends it by the slip, caps it at Coulomb's, and carries it onto the tangent plane when the
// contact's normal turns (its length kept, as LIGGGHTS rotates its shear history); both families.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/hertz_mindlin.h"
#include "contact/soft_pair.h"

// A named namespace of its own: the file's constants are unique in any unity grouping of the tests.
namespace peensim::contact::soft_pair_cases {
namespace {

const ElasticMaterial kSteel{200e9, 0.3};
constexpr double kR = 1e-3;  // m, a 2 mm shot
const double kMass = 7800.0 * 4.0 / 3.0 * M_PI * kR * kR * kR;

SoftPair linear_pair() {
    SoftPair p = hertz_pair(kSteel, kSteel, kR, kInfinite, kMass, kInfinite, 1.0, 0.1);
    p.family = SoftFamily::linear_spring_dashpot;
    p.normal_stiffness_n_per_m = 1e7;
    p.tangential_stiffness_n_per_m = 1e7;
    return p;
}

TEST(SoftPairState, TheTangentialSpringIsTheLawsPerContactState) {
    for (const SoftPair& p : {hertz_pair(kSteel, kSteel, kR, kInfinite, kMass, kInfinite, 1.0, 0.1), linear_pair()}) {
        const double d = 1e-6, fn = soft_normal_force(p, d, 0.0);
        SoftContactState state{};  // a contact's start: zeros
        const Vec3 f = soft_tangential_force(p, d, fn, Vec3::Zero(), Vec3(1e-9, 0, 0), state);
        // Stuck: the state holds the slip, the force is the spring's.
        EXPECT_EQ(state[0], 1e-9);
        EXPECT_EQ(state[1], 0.0);
        EXPECT_LT(f.x(), 0.0);
        const Vec3 again = soft_tangential_force(p, d, fn, Vec3::Zero(), Vec3::Zero(), state);
        EXPECT_EQ(again, f);  // no slip: the same force, from the state alone
        // The normal turns by 30 deg about y: the spring is carried onto the new plane, length kept.
        const Vec3 n = Vec3(std::sin(M_PI / 6), 0.0, std::cos(M_PI / 6));
        soft_turn_state(p, state, n);
        const Vec3 spring(state[0], state[1], state[2]);
        EXPECT_NEAR(spring.dot(n), 0.0, 1e-24);
        EXPECT_NEAR(spring.norm(), 1e-9, 1e-24);
        // A spring along the new normal has no plane to go to: it is dropped.
        state = {0.0, 0.0, 2e-9};
        soft_turn_state(p, state, Vec3::UnitZ());
        EXPECT_EQ(state, (SoftContactState{0.0, 0.0, 0.0}));
    }
}

}  // namespace
}  // namespace peensim::contact::soft_pair_cases
