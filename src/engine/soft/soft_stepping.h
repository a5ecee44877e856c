// The soft scheme (`accuracy.scheme: soft`): the event core's flights and predictions
// (engine/event/event_core.h) between contacts, and a pool of soft-sphere contacts (soft_pool.h)
// for the contacts themselves. A touch that is an impact (or any touch on a moving surface that
// approaches or presses the shot) hands the shot to the pool, which integrates its soft contacts
// with the others' and hands it back when it leaves; the pool's steps take their turn with the
// events in time order. Slower touches on still surfaces stay the core's rigid rest (sustained
// contact, sleep). A load at rest is never handed to time stepping: time stepping has no soft
// contacts and would resolve an impact into the load rigidly.
#pragma once

#include <memory>
#include <vector>

#include "engine/event/event_core.h"
#include "engine/event/hand_off_pool.h"
#include "engine/soft/soft_pool.h"
#include "engine/stepper.h"
#include "model/model.h"

namespace peensim {

class SoftStepping final : public Stepper, private HandOffPool, private SoftSurroundings {
public:
    explicit SoftStepping(std::shared_ptr<const Model> model);
    ~SoftStepping() override;

    std::string_view name() const override { return "soft"; }
    void advance(SimulationState& state, double t_end_s, double pause_at_s, std::vector<ImpactRecord>& impacts) override;
    const StepStats& stats() const override { return core_.stats(); }
    // As the event scheme's: restart points every EventCore::kRestartInterval and after every work
    // budget, where the pool's contacts are in the state (SimulationState::soft_contacts).
    bool at_restart_point() const override { return !core_.started(); }
    void state_changed() override { core_.close_interval(); }
    void shots_added(SimulationState& state, const std::vector<int>& shots) override;

private:
    // The pool takes shot i in at t (its touch approaching at `approach`, m/s, with `law`).
    void to_pool(int i, double t, const Vec3& p, const Vec3& v, double approach, const contact::SoftLaw* law, SimulationState& state,
                 std::vector<ImpactRecord>& impacts);
    // The members that left the pool go on in the core (at the pool's time).
    void take_exits(SimulationState& state);

    // HandOffPool: what the core asks of the pool.
    bool contains(int shot) const override { return pool_.contains(shot); }
    Vec3 position(int shot, double t) const override { return pool_.position(shot, t); }
    Vec3 velocity(int shot, double t) const override { return pool_.velocity(shot, t); }
    Vec3 spin(int shot) const override { return pool_.spin(shot); }
    bool take_wall_contact(int shot, double t, const Vec3& p, const Vec3& v, double approach, const Component& comp, const WallEvent& w,
                           SimulationState& state, std::vector<ImpactRecord>& impacts) override;
    bool take_pair_contact(int i, int j, double t, const Vec3& v_i, const Vec3& v_j, double approach, SimulationState& state,
                           std::vector<ImpactRecord>& impacts) override;
    void predicted(int shot, const std::vector<int>& members) override;
    double next_step_end() const override { return pool_.next_step_end(); }
    double step(SimulationState& state, std::vector<ImpactRecord>& impacts) override;
    void finish_interval(double t, SimulationState& state, std::vector<ImpactRecord>& impacts) override;
    void grow(std::size_t n) override { pool_.grow(n); }
    void restore(const SimTime& epoch, SimulationState& state) override;
    void settle(SimulationState& state) override { take_exits(state); }

    // SoftSurroundings: what the pool reads of, and tells, the core.
    void shots_in_box(const Vec3& lo, const Vec3& hi, std::vector<int>& out) const override { core_.pairs().overlapping(lo, hi, out); }
    void set_box(int shot, const Vec3& lo, const Vec3& hi) override;
    bool path_of(int shot, double t, Trajectory& out) const override;
    void joined(int shot, double t) override;
    void moved(int shot, const Vec3& p, const Vec3& v, double t) override;

    std::shared_ptr<const Model> model_;
    EventCore core_;
    SoftPool pool_;
    std::vector<SoftExit> exits_;  // scratch: members that left the pool
};

}  // namespace peensim
