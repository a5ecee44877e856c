// The event-driven scheme's sustained contact (resting, rolling, sliding): a shot that touches
// surfaces or other shot without bouncing is advanced in short substeps, time stepping's treatment
// at each substep's end: every surface and shot it touches takes the approach away through the
// pair's law (friction on surfaces), overlaps are removed by moving it out, and a shot that stays
// still long enough falls asleep. Reads the other shot (held like walls) and the surfaces; changes
// only the shot it resolves, the health counters and the impact log (a slide into another surface
// fast enough is a rebound, an impact if at least the impact speed).
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "common/sim_time.h"
#include "engine/event/pair_predictor.h"
#include "engine/event/shot_record.h"
#include "engine/event/wall_predictor.h"
#include "engine/impact_record.h"
#include "engine/simulation_state.h"
#include "model/model.h"

namespace peensim {

class SustainedContact {
public:
    // resting_speed_m_per_s: slower is still (sleep), and no rebound.
    SustainedContact(std::shared_ptr<const Model> model, double resting_speed_m_per_s);

    // How shot i goes on after a substep: flying (it touches nothing), sleeping (still for
    // kQuietSubsteps substeps), or sustained on `support` (the contact normal gravity presses on most).
    struct Next {
        Vec3 position_m;
        Vec3 velocity_m_per_s;
        Vec3 support = Vec3::Zero();
        EventMotion motion = EventMotion::sustained;
    };

    // The end of shot i's substep at t (s, the scheme's clock since `epoch`), its centre p (m) and
    // velocity v (m/s) there. Updates the shot's in_flight flag and still-substep count.
    Next end_of_substep(int i, double t, Vec3 p, Vec3 v, const SimTime& epoch, std::span<EventShot> shots,
                        const std::vector<unsigned char>& active, const PairPredictor& pairs, const WallPredictor& walls,
                        SimulationState& state, std::vector<ImpactRecord>& impacts);

    static constexpr int kQuietSubsteps = 40;  // still substeps (2 ms) before a resting shot sleeps

private:
    std::shared_ptr<const Model> model_;
    Vec3 g_ = Vec3::Zero();        // m/s2
    double resting_speed_ = 0.0;   // m/s
    bool contact_state_ = false;   // a law keeps state per contact (SimulationState::contacts)
    std::vector<int> neighbours_;  // scratch
    std::vector<double> scratch_;  // an instantaneous contact's state (zeros)
};

}  // namespace peensim
