// A pool of shot that a scheme built on the event core (event_core.h) integrates by its own method:
// the core hands it the contacts it asks for and leaves its members alone until they come back.
// The soft scheme's pool of soft-sphere contacts is one (engine/soft/soft_stepping.h); the event
// scheme has none. The core asks through this interface only, so it knows nothing of how a pool
// moves its members.
#pragma once

#include <cstddef>
#include <vector>

#include "common/vec.h"
#include "engine/event/wall_event.h"
#include "engine/impact_record.h"
#include "engine/simulation_state.h"

namespace peensim {

struct Component;

class HandOffPool {
public:
    virtual ~HandOffPool() = default;

    // Whether shot i is a member now, and a member's centre (m), velocity (m/s) and spin (rad/s) at
    // t (s, the core's clock).
    virtual bool contains(int shot) const = 0;
    virtual Vec3 position(int shot, double t) const = 0;
    virtual Vec3 velocity(int shot, double t) const = 0;
    virtual Vec3 spin(int shot) const = 0;

    // Shot i touches a component at t (the event w, at centre p with velocity v, approaching the
    // surface at `approach` m/s, < 0: separating): true if the pool takes it in (the core then
    // resolves nothing), false to let the core resolve it rigidly.
    virtual bool take_wall_contact(int shot, double t, const Vec3& p, const Vec3& v, double approach, const Component& comp,
                                   const WallEvent& w, SimulationState& state, std::vector<ImpactRecord>& impacts) = 0;
    // Shots i and j touch at t approaching at `approach` (m/s): true if the pool takes both in.
    virtual bool take_pair_contact(int i, int j, double t, const Vec3& v_i, const Vec3& v_j, double approach, SimulationState& state,
                                   std::vector<ImpactRecord>& impacts) = 0;
    // Shot i was just predicted; `members` are the pool's members whose boxes overlap its own.
    virtual void predicted(int shot, const std::vector<int>& members) = 0;

    // The pool's steps take their turn with the events in time order: the end of its next step (s,
    // the core's clock; infinity: none), and the step itself (returns the pool's time after it).
    virtual double next_step_end() const = 0;
    virtual double step(SimulationState& state, std::vector<ImpactRecord>& impacts) = 0;
    // A restart point at t (s, the core's clock) comes next: the pool steps exactly there and puts
    // what outlives it into the state.
    virtual void finish_interval(double t, SimulationState& state, std::vector<ImpactRecord>& impacts) = 0;

    // Room for n shot.
    virtual void grow(std::size_t n) = 0;
    // The core starts afresh from the state (its first pass done: every flight and box set): the
    // pool takes back the contacts the state holds, then (settle) the core predicts the others and
    // the pool hands back those that left meanwhile.
    virtual void restore(const SimTime& epoch, SimulationState& state) = 0;
    virtual void settle(SimulationState& state) = 0;
};

}  // namespace peensim
