// Finds flights that passed through the vibrating sonotrode inside a step without the engine
// noticing (a missed contact: the shot is above the plate at both ends of the step, but its parabola
// dipped into the moving plate in between). The engine only sees the step ends, so a check at the
// step ends alone cannot find these.
//
// For the plate sonotrode of TestScene (top face z = plate_top_m in its own frame, vibrating along
// world z, shot over its footprint). Per shot and step, the checked flight starts at the step start,
// or at the shot's last logged sonotrode impact in that step (the sonotrode must be logged); it is
// checked only if the engine's end state is exactly that free flight (nothing else, logged or not,
// acted on the shot), and then sampled densely against the plate's closed-form motion.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/impact_record.h"
#include "engine/simulation_state.h"
#include "model/model.h"

namespace peensim::testing {

struct CrossingReport {
    std::uint64_t flights_checked = 0;  // free flights sampled
    std::uint64_t missed_contacts = 0;  // flights that went deeper than the tolerance into the plate
    double deepest_m = 0.0;             // m, most negative gap found (0 if none)
    std::string first_example;          // numbers of the first missed contact, for the report
};

class SonotrodeCrossingCheck {
public:
    // tolerance_m: a gap above -tolerance counts as touching, not crossing (m).
    // The flight is sampled samples_per_period times per vibration period, at least 8 times a step.
    SonotrodeCrossingCheck(const Model& model, double plate_top_m, double tolerance_m = 1e-9, double samples_per_period = 64.0);

    void before_step(const SimulationState& state);
    void after_step(const SimulationState& state, const std::vector<ImpactRecord>& impacts);

    const CrossingReport& report() const { return report_; }

private:
    const Model& model_;
    double plate_top_m_;
    double tolerance_m_;
    double samples_per_period_;
    ShotArrays before_;
    SimTime t0_;
    CrossingReport report_;
    std::vector<int> last_impact_;  // per shot: index into the step's impacts of its last one, -1 none
};

}  // namespace peensim::testing
