// Per-contact law state (contact_law.h state_per_contact, engine/contact_states.h), added by a law
// in this test without touching the schemes: the law counts how long each sustained contact has
// lasted. A shot dropped on the still plate bounces, lands and rests: its contact with the plate
// is one contact that lasts, its state the time it has rested; impacts are handed zeros; lifting
// the shot ends the contact, landing again starts a new one from zero; a checkpoint keeps it.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <vector>

#include "app/checkpoint/checkpoint.h"
#include "engine/simulation.h"
#include "support/temp_dir.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

// The impulse law's rebounds and friction, and one double per contact: the time (s) it has lasted.
class ContactAgeLaw final : public contact::SurfaceLaw {
public:
    explicit ContactAgeLaw(std::shared_ptr<const contact::SurfaceLaw> inner) : inner_(std::move(inner)) {}
    std::string_view name() const override { return "contact-age"; }
    int state_per_contact() const override { return 1; }
    contact::SurfaceContactResponse impact(const contact::SurfaceContactInput& in, std::span<double> triangles) const override {
        // An impact is a contact of its own: it starts from zeros.
        if (in.contact_state.size() != 1 || in.contact_state[0] != 0.0) ++bad_impact_states;
        return inner_->impact(in, triangles);
    }
    contact::SurfaceContactResponse sustain(const contact::SurfaceContactInput& in, std::span<double> triangles) const override {
        if (in.contact_state.size() == 1) in.contact_state[0] += in.dt;
        return inner_->sustain(in, triangles);
    }
    mutable int bad_impact_states = 0;  // the test's own tally (a real law keeps nothing in itself)

private:
    std::shared_ptr<const contact::SurfaceLaw> inner_;
};

constexpr double kDuration = 0.5;  // s

struct Rest {
    std::shared_ptr<const Model> model;
    std::shared_ptr<const ContactAgeLaw> law;
    std::size_t plate = 0;
};

Rest plate_with_age_law(const TestScene& scene) {
    auto model = std::make_shared<Model>(*scene.compile());
    Rest r;
    r.plate = static_cast<std::size_t>(model->sonotrode);
    r.law = std::make_shared<const ContactAgeLaw>(model->components[r.plate].law);
    model->components[r.plate].law = r.law;
    r.model = model;
    return r;
}

TestSceneSpec still_plate(const std::string& scheme) {
    TestSceneSpec spec;
    spec.amplitude_m = 0.0;
    spec.sonotrode = {0.6, 1e3, 0.71, 0.1};
    spec.log = {"sonotrode"};
    spec.duration_s = kDuration;
    spec.scheme = scheme;
    return spec;
}

class ContactState : public ::testing::TestWithParam<std::string> {};

// Steps `sim` to time t_s (s), collecting its impacts; returns the longest step (s). By hand: the
// test edits the state mid-run (lifts the shot at t_s), and RunLoop ends only at restart points.
double run_to(Simulation& sim, double t_s, std::vector<ImpactRecord>& all) {
    std::vector<ImpactRecord> impacts;
    double largest_step = 0.0;
    while (!sim.finished() && sim.state().time.seconds() < t_s) {
        const double before = sim.state().time.seconds();
        sim.step(impacts, t_s);
        largest_step = std::max(largest_step, sim.state().time.seconds() - before);
        all.insert(all.end(), impacts.begin(), impacts.end());
        impacts.clear();
    }
    return largest_step;
}

TEST_P(ContactState, ARestingShotsContactLastsAndRemembersHowLong) {
    const TestScene scene(still_plate(GetParam()));
    const Rest rest = plate_with_age_law(scene);
    Simulation sim(rest.model);
    const double R = rest.model->max_shot_radius_m;
    sim.edit_state([&](SimulationState& s) { set_shot(s, 0, Vec3(0.0, 0.0, R + 2e-3), Vec3::Zero()); });
    std::vector<ImpactRecord> all;
    const double t_lift = 0.35;  // s
    const double largest_step = run_to(sim, t_lift, all);
    ASSERT_FALSE(all.empty());
    // One contact: shot 0 on the plate.
    const auto only_contact = [&]() -> const ContactStates::Entry& {
        const ContactStates& contacts = sim.state().contacts;
        EXPECT_EQ(contacts.entries().size(), 1u);
        EXPECT_EQ(contacts.entries().begin()->first, (ContactStates::Key{0, static_cast<int>(rest.plate)}));
        return contacts.entries().begin()->second;
    };
    ASSERT_EQ(sim.state().contacts.entries().size(), 1u);
    // It landed for good a flight after its last rebound (C = 0.6: vn_out = 0.6 vn_in).
    const double t_land = all.back().time_s + 2.0 * all.back().vn_out_m_per_s / 9.81;
    const double rested = sim.state().time.seconds() - t_land;
    ASSERT_GT(rested, 0.1);
    const double age = only_contact().values[0];
    std::cout << "[ contact  ] " << GetParam() << ": rested " << rested << " s, contact age " << age << " s\n";
    if (GetParam() == "step") {
        // Every step's sustained contact adds its step: the whole rest, within two steps.
        EXPECT_NEAR(age, rested, 2.0 * largest_step + 1e-3);
    } else {
        // The event scheme's substeps add theirs until the shot sleeps (40 still substeps), then
        // time stepping's steps once the resting load is handed over: part of the rest, never more.
        EXPECT_GT(age, 1e-3);
        EXPECT_LE(age, rested + 1e-3);
    }

    // Lifted 3 mm: in flight the contact has ended; it lands (24.7 ms later), bounces and rests
    // again: a new contact, younger than the time since the lift.
    sim.edit_state([&](SimulationState& s) { set_shot(s, 0, Vec3(0.0, 0.0, R + 3e-3), Vec3::Zero()); });
    run_to(sim, t_lift + 0.01, all);
    EXPECT_TRUE(sim.state().contacts.entries().empty());
    run_to(sim, kDuration, all);
    ASSERT_EQ(sim.state().contacts.entries().size(), 1u);
    const double age_again = only_contact().values[0];
    EXPECT_GT(age_again, 0.0);
    EXPECT_LT(age_again, kDuration - t_lift - 0.0247);
    EXPECT_EQ(rest.law->bad_impact_states, 0);

    // A checkpoint keeps the contact and its state.
    TempDir dir;
    const std::string path = (dir.path / "checkpoint.bin").string();
    Checkpoint c;
    c.scene_hash = rest.model->scene_hash;
    c.state = sim.state();
    save_checkpoint(path, c);
    const Checkpoint back = load_checkpoint(path);
    ASSERT_EQ(back.state.contacts.entries().size(), 1u);
    EXPECT_EQ(back.state.contacts.entries().begin()->second.values, sim.state().contacts.entries().begin()->second.values);
    EXPECT_EQ(back.state.contacts.resolutions(), sim.state().contacts.resolutions());
}

INSTANTIATE_TEST_SUITE_P(Schemes, ContactState, ::testing::Values("step", "event"));

}  // namespace
}  // namespace peensim::testing
