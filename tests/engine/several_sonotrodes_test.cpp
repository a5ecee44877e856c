// Several vibrating components: a plate inside the chamber made a second sonotrode, vibrating,
// while the first (the chamber's floor, where the shot are placed) stands still. A shot dropped on
// the plate is thrown by it as by any sonotrode: both schemes see the same impacts on it within
// noise, every impact on its top face, and the event scheme takes that face as an exact vibrating
// plane (its own face kernel, not conservative advancement).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "engine/simulation.h"
#include "support/run_through_loop.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

constexpr double kPlateTop = 7e-3;  // m, world z of the plate's top face at rest

struct PlateRun {
    std::vector<ImpactRecord> impacts;
    SimulationState state;
    StepStats stats;
    std::shared_ptr<const Model> model;
};

PlateRun drop_on_second_sonotrode(const std::string& scheme) {
    TestSceneSpec spec;
    spec.amplitude_m = 0.0;  // the first sonotrode (the floor) stands still
    PartSpec plate;
    plate.shape = PartShape::plate;
    plate.size_m = Vec3(12e-3, 12e-3, 2e-3);
    plate.center_m = Vec3(0.0, 0.0, kPlateTop - 1e-3);
    spec.part = plate;
    spec.log = {"part"};
    spec.shot_count = 16;
    spec.duration_s = 4.0;
    spec.scheme = scheme;
    const TestScene scene(spec);
    PlateRun r;
    r.model = scene.compile(
        {"components[part].role=sonotrode", "components[part].vibration={amplitude: 20 um, frequency: 20 kHz, axis: [0, 0, 1]}"});
    Simulation sim(r.model);
    const double R = r.model->max_shot_radius_m;
    // 16 shot dropped on the plate from 2 mm, on a 4 x 4 grid 2.5 mm apart.
    sim.edit_state([&](SimulationState& s) {
        for (int k = 0; k < 16; ++k)
            set_shot(s, static_cast<std::size_t>(k), Vec3(2.5e-3 * (k % 4 - 1.5), 2.5e-3 * (k / 4 - 1.5), kPlateTop + R + 2e-3),
                     Vec3::Zero());
    });
    r.impacts = run_collecting_impacts(sim);
    r.state = sim.state();
    r.stats = sim.scheme().stats();
    return r;
}

struct Mean {
    double value = 0.0;           // m/s
    double standard_error = 0.0;  // m/s
};

Mean mean_vn(const std::vector<ImpactRecord>& impacts) {
    double sum = 0.0, sum2 = 0.0;
    for (const ImpactRecord& i : impacts) sum += i.vn_in_m_per_s, sum2 += i.vn_in_m_per_s * i.vn_in_m_per_s;
    const double n = static_cast<double>(impacts.size()), mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

TEST(SeveralSonotrodes, ASecondVibratingSonotrodeThrowsShotAsTheFirstDoes) {
    const PlateRun event = drop_on_second_sonotrode("event");
    const PlateRun step = drop_on_second_sonotrode("step");
    const Model& m = *event.model;
    const int plate = m.component_index("part");
    ASSERT_EQ(m.components[static_cast<std::size_t>(plate)].role, ComponentRole::sonotrode);
    EXPECT_EQ(m.sonotrode, m.component_index("sonotrode"));  // the shot are placed on the first
    for (const PlateRun* r : {&event, &step}) {
        EXPECT_EQ(r->state.health.serious(), 0u);
        EXPECT_GT(r->impacts.size(), 500u);  // thrown again and again
        for (const ImpactRecord& i : r->impacts) {
            ASSERT_EQ(i.component, plate);
            // On the top face (component frame: the plate at rest), not its sides or bottom.
            EXPECT_NEAR(i.point_m.z(), kPlateTop, 1e-9);
        }
    }
    // The event scheme found those contacts on the face's exact vibrating plane.
    EXPECT_GT(event.stats.touch_searches, 0u);
    // The same process: impact rates and mean normal speeds within 4 standard errors (the bounces
    // counted as independent, which they are not: over 1 s the means differed by 5 such errors,
    // over these 4 s, measured, 2.860 against 2.876 m/s and 6352 against 6676 impacts).
    const double n_event = static_cast<double>(event.impacts.size()), n_step = static_cast<double>(step.impacts.size());
    EXPECT_NEAR(n_event, n_step, 4.0 * std::sqrt(n_event + n_step));
    const Mean e = mean_vn(event.impacts), s = mean_vn(step.impacts);
    const double v_event = e.value, v_step = s.value;
    EXPECT_GT(v_event, 0.3);  // m/s: the plate (2 pi f A = 2.5 m/s peak) throws it, not a settling drop
    EXPECT_NEAR(v_event, v_step, 4.0 * std::hypot(e.standard_error, s.standard_error));
    std::cout << "[ plate    ] event " << event.impacts.size() << " impacts, mean vn " << v_event << " m/s; step " << step.impacts.size()
              << ", " << v_step << " m/s\n";
}

}  // namespace
}  // namespace peensim::testing
