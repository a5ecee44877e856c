// The `hertz-mindlin` law (contact/hertz_mindlin_law.h): its rigid limit for the rigid schemes
// (exact values), its soft-sphere constants for the soft scheme, what it needs of a scene, and
// that a key two laws declare means the same in both (one schema entry serves them).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "contact/hertz_mindlin_law.h"
#include "contact/law_registry.h"
#include "contact/restitution.h"

namespace peensim::contact {
namespace {

const ElasticMaterial kSteel{200e9, 0.3};
const ElasticMaterial kAluminium{70e9, 0.33};
constexpr double kR = 1e-3;  // m
const double kMass = 7800.0 * 4.0 / 3.0 * M_PI * kR * kR * kR;

SurfaceContactInput hit(const Vec3& v) {
    SurfaceContactInput in;
    in.v_shot = v;
    in.v_surface = Vec3::Zero();
    in.normal = Vec3::UnitZ();
    return in;
}

TEST(HertzMindlinLaw, RigidLimitGripsAtFiveSeventhsOrSlidesAtCoulomb) {
    const HertzMindlinSurfaceLaw law({0.8, 0.2, 0.0}, kSteel, kAluminium, kR, kMass);
    // Near normal (vt/vn 0.25 < 2/7 / (f (1 + e)) = 0.79): the contact point grips, 5/7 kept.
    const SurfaceContactResponse grip = law.impact(hit(Vec3(0.5, 0.0, -2.0)), {});
    EXPECT_DOUBLE_EQ(grip.v_shot.x(), 0.5 * 5.0 / 7.0);
    EXPECT_DOUBLE_EQ(grip.v_shot.z(), 0.8 * 2.0);
    EXPECT_DOUBLE_EQ(grip.vn_in, 2.0);
    EXPECT_DOUBLE_EQ(grip.vn_out, 1.6);
    // Grazing (vt/vn 3): Coulomb's impulse f (1 + e) vn = 0.72 m/s taken from 6 m/s.
    const SurfaceContactResponse slide = law.impact(hit(Vec3(0.0, 6.0, -2.0)), {});
    EXPECT_DOUBLE_EQ(slide.v_shot.y(), 6.0 - 0.2 * 1.8 * 2.0);
    EXPECT_DOUBLE_EQ(slide.v_shot.z(), 1.6);
    // Separating: unchanged.
    EXPECT_FALSE(law.impact(hit(Vec3(1.0, 0.0, 2.0)), {}).approaching);
    EXPECT_EQ(law.impact(hit(Vec3(1.0, 0.0, 2.0)), {}).v_shot, Vec3(1.0, 0.0, 2.0));
}

TEST(HertzMindlinLaw, RigidLimitBetweenShotKeepsMomentum) {
    const HertzMindlinShotShotLaw law({0.9, 0.1, 0.0}, kSteel, kR, kMass);
    ShotShotInput in{Vec3(1.0, 3.0, 0.0), Vec3(-1.0, 0.0, 0.0), Vec3::UnitX(), ShotShotMode::law};
    const ShotShotResponse r = law.respond(in);
    EXPECT_NEAR((r.v_i + r.v_j - in.v_i - in.v_j).norm(), 0.0, 1e-15);
    // Normal: the relative approach 2 m/s reverses at e; tangential slip 3 m/s (relative) loses
    // Coulomb's f (1 + e) 2 = 0.38 m/s (3 > 0.38 * 7 / 2: it slides), shared.
    EXPECT_DOUBLE_EQ((r.v_j - r.v_i).x(), 0.9 * 2.0);
    EXPECT_NEAR((r.v_i - r.v_j).y(), 3.0 - 0.38, 1e-15);
    EXPECT_DOUBLE_EQ(r.vn_in, 2.0);
    // A held partner (a pile's substeps): i takes it all; sustained: the approach stops, no slip lost.
    in.j_held = true;
    in.mode = ShotShotMode::sustained;
    const ShotShotResponse held = law.respond(in);
    EXPECT_DOUBLE_EQ(held.v_i.x(), -1.0);
    EXPECT_DOUBLE_EQ(held.v_i.y(), 3.0);
    EXPECT_EQ(held.v_j, in.v_j);
}

TEST(HertzMindlinLaw, RigidLimitBetweenShotOfTwoSizesWeighsByMass) {
    // A shot mix: i of mass 1, j of mass 4 (a shot 1.59 times the diameter). The same relative
    // outcome as for equal masses (normal reversed at e, slip reduced by Coulomb's impulse), the
    // change of each velocity in inverse proportion to its mass: i takes 4/5, j 1/5.
    const HertzMindlinShotShotLaw law({0.9, 0.1, 0.0}, kSteel, kR, kMass);
    ShotShotInput in{Vec3(1.0, 3.0, 0.0), Vec3(-1.0, 0.0, 0.0), Vec3::UnitX(), ShotShotMode::law};
    in.mass_i_kg = 1.0;
    in.mass_j_kg = 4.0;
    const ShotShotResponse r = law.respond(in);
    EXPECT_NEAR((1.0 * r.v_i + 4.0 * r.v_j - 1.0 * in.v_i - 4.0 * in.v_j).norm(), 0.0, 1e-14);
    EXPECT_NEAR((r.v_j - r.v_i).x(), 0.9 * 2.0, 1e-15);
    EXPECT_NEAR((r.v_i - r.v_j).y(), 3.0 - 0.38, 1e-15);
    // Exchange (1 + e) dV = -3.8 along x, -(0.38) along y of the slip: i gets 4/5 of it.
    EXPECT_NEAR(r.v_i.x(), 1.0 - 0.8 * 3.8, 1e-15);
    EXPECT_NEAR(r.v_j.x(), -1.0 + 0.2 * 3.8, 1e-15);
    EXPECT_NEAR(r.v_i.y(), 3.0 - 0.8 * 0.38, 1e-15);
    EXPECT_NEAR(r.v_j.y(), 0.2 * 0.38, 1e-15);
}

TEST(HertzMindlinLaw, SoftConstantsAreThePairsWithTheDampingOfTheApproach) {
    const HertzMindlinSurfaceLaw law({0.9, 0.1, 0.5}, kSteel, kAluminium, kR, kMass);
    ASSERT_EQ(law.soft(), &law);
    const SoftPair slow = law.contact(0.4), fast = law.contact(8.0);
    EXPECT_DOUBLE_EQ(slow.E_star_pa, hertz_pair(kSteel, kAluminium, kR, kInfinite, kMass, kInfinite, 1.0, 0.1).E_star_pa);
    EXPECT_EQ(slow.R_star_m, kR);
    EXPECT_EQ(slow.m_star_kg, kMass);
    EXPECT_EQ(slow.friction, 0.1);
    EXPECT_DOUBLE_EQ(slow.beta, hertz_beta(0.9));                                // below plastic_speed: e
    EXPECT_DOUBLE_EQ(fast.beta, hertz_beta(normal_restitution(8.0, 0.9, 0.5)));  // above: e (V/V0)^-1/4
    const HertzMindlinShotShotLaw pairs({0.9, 0.1, 0.0}, kSteel, kR, kMass);
    EXPECT_DOUBLE_EQ(pairs.contact(3.0).R_star_m, 0.5 * kR);
    EXPECT_DOUBLE_EQ(pairs.contact(3.0).m_star_kg, 0.5 * kMass);
    EXPECT_DOUBLE_EQ(pairs.contact(30.0).beta, hertz_beta(0.9));  // plastic_speed 0: e at every speed
}

TEST(HertzMindlinLaw, NeedsTheElasticConstantsOfBothMaterials) {
    const LawEntry* hm = find_law("hertz-mindlin");
    ASSERT_NE(hm, nullptr);
    ASSERT_NE(hm->make_shot_shot, nullptr);
    ParameterValues v;
    v.parameters = {{"e", {0.9}}, {"f", {0.1}}, {"plastic_speed", {0.0}}};
    SurfacePair pair;
    pair.shot_diameter_m = 2e-3;
    pair.shot_density_kg_per_m3 = 7800.0;
    pair.material = "aluminium";
    pair.shot_material = "steel";
    pair.shot_elastic = kSteel;
    try {
        (void)hm->make_surface(v, pair);
        FAIL() << "expected a refusal";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("materials.aluminium.youngs_modulus"), std::string::npos) << e.what();
    }
    pair.surface_elastic = kAluminium;
    EXPECT_NE(hm->make_surface(v, pair)->soft(), nullptr);
    ShotShotPair shots;
    shots.shot_diameter_m = 2e-3;
    shots.shot_density_kg_per_m3 = 7800.0;
    try {
        (void)hm->make_shot_shot(v, shots);
        FAIL() << "expected a refusal";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("shot.material"), std::string::npos) << e.what();
    }
    // The rigid laws have no soft form (the soft scheme refuses them).
    const ParameterValues impulse{{{"C0", {0.9}}, {"V0", {0.1}}}};
    EXPECT_EQ(find_law("impulse")->make_shot_shot(impulse, shots)->soft(), nullptr);
}

// One schema entry serves a key every law that declares it: it must mean the same to each (same
// dimension, range, default and list-ness). A V0 that the impulse law bounds above 0 with a
// default of 0.5 m/s was once read for another law whose 0 meant "off".
TEST(HertzMindlinLaw, AKeySeveralLawsDeclareMeansTheSameInEach) {
    for (const LawEntry& a : law_catalogue())
        for (const LawEntry& b : law_catalogue())
            for (const auto& pa : {a.surface_parameters, a.shot_shot_parameters})
                for (const auto& pb : {b.surface_parameters, b.shot_shot_parameters})
                    for (const LawParameter& x : pa)
                        for (const LawParameter& y : pb) {
                            if (x.name != y.name) continue;
                            EXPECT_EQ(x.dimension, y.dimension) << a.name << "/" << b.name << " " << x.name;
                            EXPECT_EQ(x.default_value, y.default_value) << a.name << "/" << b.name << " " << x.name;
                            EXPECT_EQ(x.list, y.list) << a.name << "/" << b.name << " " << x.name;
                            EXPECT_EQ(x.range.lo, y.range.lo) << a.name << "/" << b.name << " " << x.name;
                            EXPECT_EQ(x.range.hi, y.range.hi) << a.name << "/" << b.name << " " << x.name;
                            EXPECT_EQ(x.range.lo_open, y.range.lo_open) << a.name << "/" << b.name << " " << x.name;
                        }
}

}  // namespace
}  // namespace peensim::contact
