// One contact policy (contact/contact_policy.h) for every scheme: the same contact situations run
// through time stepping, the event scheme and the soft scheme, on the same law (hertz-mindlin, whose
// instantaneous limit the rigid schemes take), are classified the same way: an impact (logged and
// counted) exactly when the normal approach reaches `accuracy.impact_speed`, else a slow contact.
// A scheme may resolve a slow contact its own way (follow its rebound, or stop it); it may not
// call it something else.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "engine/simulation.h"
#include "support/run_through_loop.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

struct Classified {
    std::uint64_t impacts = 0;  // on the floor (the still sonotrode), and logged records of them
    std::size_t logged = 0;
    std::uint64_t slow_contacts = 0;  // on the floor
    std::uint64_t shot_shot_impacts = 0, shot_shot_slow = 0;
    double first_vn_in = 0.0;  // m/s, the first logged impact's approach
};

constexpr double kLine = 0.05;  // m/s, accuracy.impact_speed (the default)

TestSceneSpec still_box(const std::string& scheme, int shot_count, double duration_s) {
    TestSceneSpec spec;
    spec.scheme = scheme;
    spec.soft = SoftSpec{};  // hertz-mindlin for every pair, in every scheme
    spec.soft->e_sonotrode = spec.soft->e_shot_shot = 0.8;
    spec.amplitude_m = 0.0;
    spec.shot_count = shot_count;
    spec.gravity_m_per_s2 = Vec3::Zero();
    spec.chamber_size_m = Vec3(40e-3, 40e-3, 40e-3);
    spec.duration_s = duration_s;
    spec.log = {"sonotrode"};
    return spec;
}

Classified run(const TestSceneSpec& spec, const std::function<void(SimulationState&, double R)>& place) {
    const TestScene scene(spec);
    const auto model = scene.compile();
    Simulation sim(model);
    const double R = model->max_shot_radius_m;
    sim.edit_state([&](SimulationState& s) { place(s, R); });
    Classified c;
    run_through_loop(sim, {.after_step = [&](const Simulation&, const std::vector<ImpactRecord>& step) {
                         for (const ImpactRecord& r : step)
                             if (c.logged++ == 0) c.first_vn_in = r.vn_in_m_per_s;
                     }});
    const SimulationState& s = sim.state();
    c.impacts = s.impacts_per_component.at(0);
    c.slow_contacts = s.slow_contacts_per_component.at(0);
    c.shot_shot_impacts = s.shot_shot_impacts;
    c.shot_shot_slow = s.shot_shot_slow_contacts;
    EXPECT_EQ(s.health.serious(), 0u) << spec.scheme;
    return c;
}

const std::vector<std::string> kSchemes{"step", "event", "soft"};

// A shot flying straight at the still floor, without gravity, at speeds across the impact line:
// one contact, an impact exactly when v >= the line.
TEST(ContactPolicy, ASurfaceTouchIsAnImpactInEverySchemeExactlyFromTheImpactLine) {
    for (const double factor : {0.3, 0.9, 1.1, 3.0, 40.0}) {
        const double v = factor * kLine;
        for (const std::string& scheme : kSchemes) {
            const Classified c = run(still_box(scheme, 1, 3e-3 / v),
                                     [&](SimulationState& s, double R) { set_shot(s, 0, Vec3(0.0, 0.0, R + 1e-3), Vec3(0.0, 0.0, -v)); });
            const bool impact = factor >= 1.0;
            EXPECT_EQ(c.impacts, impact ? 1u : 0u) << scheme << " at " << v << " m/s";
            EXPECT_EQ(c.logged, impact ? 1u : 0u) << scheme << " at " << v << " m/s";
            EXPECT_EQ(c.slow_contacts, impact ? 0u : 1u) << scheme << " at " << v << " m/s";
            if (impact) {
                EXPECT_NEAR(c.first_vn_in, v, 1e-6 * v) << scheme;
            }
        }
    }
}

// Two shot flying head-on at each other, without gravity: one contact, an impact exactly when their
// approach reaches the line, else a slow one.
TEST(ContactPolicy, AShotShotTouchIsAnImpactInEverySchemeExactlyFromTheImpactLine) {
    for (const double factor : {0.3, 0.9, 1.1, 3.0, 40.0}) {
        const double v = factor * kLine;  // their approach: each flies at v / 2
        for (const std::string& scheme : kSchemes) {
            const Classified c = run(still_box(scheme, 2, 2e-3 / v), [&](SimulationState& s, double R) {
                set_shot(s, 0, Vec3(-R - 0.5e-3, 0.0, 20e-3), Vec3(0.5 * v, 0.0, 0.0));
                set_shot(s, 1, Vec3(R + 0.5e-3, 0.0, 20e-3), Vec3(-0.5 * v, 0.0, 0.0));
            });
            const bool impact = factor >= 1.0;
            EXPECT_EQ(c.shot_shot_impacts, impact ? 1u : 0u) << scheme << " at " << v << " m/s";
            EXPECT_EQ(c.shot_shot_slow, impact ? 0u : 1u) << scheme << " at " << v << " m/s";
            EXPECT_EQ(c.impacts + c.slow_contacts, 0u) << scheme;  // nothing reaches the floor
        }
    }
}

}  // namespace
}  // namespace peensim::testing
