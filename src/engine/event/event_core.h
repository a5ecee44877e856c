// The event-driven core: every shot flies its exact parabola (eq. 1) to its next collision, found
// exactly, and time jumps from one collision to the next. Cost follows the number of collisions,
// not of time steps, and there is no step to alias the plate. Two schemes are built on it: the
// event scheme (event_stepping.h: the core, and a load at rest handed to time stepping) and the
// soft scheme (engine/soft/soft_stepping.h: the core, and a pool of soft-sphere contacts that
// takes the impacts, through HandOffPool).
//
// Each shot has one pending event, the earliest of:
//   wall    its first contact with any component within its search window: static meshes by
//           MeshCollider::first_hit (a time-ordered swept-sphere walk of the BVH), the sonotrode's
//           face by vibrating_plane_toi, moving meshes (rotating part, the sonotrode's sides) by
//           conservative advancement on exact distances; or the end of a ride / substep, or
//           leaving the world box (a lost shot);
//   pair    its first contact with a neighbour (sphere_pair_toi), neighbours being the shot whose
//           flight boxes overlap its own (ShotBoxTree);
//   window  the end of the stretch of its flight searched so far (4 radii of travel, doubling
//           while nothing is found): short searches visit few BVH nodes, and the flight box
//           that neighbours are found by covers just that stretch.
// An EventQueue holds one entry per shot. A pair event remembers its partner's flight version:
// if the partner's flight changed since, the event is stale and the shot re-predicts (lazy
// invalidation). Contact laws, impact records and health counters are time stepping's.
//
// Degenerate regimes (reference event-driven-notes.md, pitfalls 1-5):
//   ride    a rebound from the sonotrode face slower than 1 mm/s while the plate accelerates into
//           the shot is a ride: the shot moves with the plate until the plate's deceleration
//           exceeds gravity, then launches with the plate's velocity (no Zeno sequence; faster
//           rebounds are followed exactly, however soon the plate catches them again);
//   rest    a touch slower than the resting speed on any other surface starts sustained contact,
//           advanced in short substeps with time stepping's sustain law (friction, no approach)
//           until the shot flies free again; a shot that stays still for a while sleeps (no
//           events) until a collision or a woken neighbour wakes it;
//   collapse a shot-shot collision within 1 us of either shot's previous one is elastic (the TC
//           rule), so clusters cannot collapse into infinitely many collisions;
//   grazing touching-and-separating at the start of a prediction is never an impact (the
//           kernels' rule), and a pair is never re-collided at the very time it just collided.
// Every self-rescheduling event (window end, substep, launch) moves time forward by a fixed minimum.
//
// Restart points. Every kRestartInterval of simulated time, and at the next point of the sync grid
// after every work budget, the core starts afresh from the state alone (every flight re-predicted,
// neighbour tree rebuilt), exactly as a run resumed from a checkpoint of that state does: so a
// resumed run equals the uninterrupted one, byte for byte. The scheme on top decides what an
// interval is (the event scheme may time-step one) and calls open_interval / start_from.
//
// Files: event_core.cpp (the loop, restart points, predictions), event_collisions.cpp (what an
// event does: rebounds, touches, rides, substeps, shot-shot collisions, losses).
#pragma once

#include <memory>
#include <vector>

#include "collision/mesh_collider.h"
#include "engine/event/event_queue.h"
#include "engine/event/hand_off_pool.h"
#include "engine/event/pair_predictor.h"
#include "engine/event/shot_motion.h"
#include "engine/event/shot_record.h"
#include "engine/event/sonotrode_face.h"
#include "engine/event/sustained_contact.h"
#include "engine/event/wall_event.h"
#include "engine/event/wall_predictor.h"
#include "engine/impact_record.h"
#include "engine/simulation_state.h"
#include "engine/step_stats.h"
#include "kernels/trajectory.h"
#include "model/model.h"

namespace peensim {

class EventCore {
public:
    using Motion = EventMotion;
    using Shot = EventShot;

    explicit EventCore(std::shared_ptr<const Model> model);

    static constexpr double kRestartInterval = 0.1;  // s
    // Simulated time (s) one advance() covers at most: it stops on a grid of this spacing (absolute
    // multiples), where the state is brought up to date for progress, checkpoints and interrupts.
    static constexpr double kSyncInterval = 1e-3;
    // The search fallback: a flight whose contact search runs out of iterations this many times in a
    // row (each kMaxAdvancement conservative-advancement steps within a hair of a moving surface,
    // gaining almost no time) goes on in sustained-contact substeps, which always advance time by
    // a substep; counted in HealthCounters::search_fallbacks. The net under "simulated time always
    // advances" (a blade turning at 1000 rpm once stalled so); rare: nozzle-gear 7 times in 30 s,
    // a shot pressed by a turning surface chattering in arcs of about 1 um (docs/user-guide.md, "Outputs": the health counters).
    static constexpr int kMaxResumedSearches = 4;
    // Work between restart points, in work units (work_units(): ~0.25 us of wall time each): at
    // least kMinWorkBudget, and kWorkPerRestart times what the last restart cost (re-predicting
    // every shot), so restarts take at most ~1/16 of the run.
    static constexpr std::uint64_t kMinWorkBudget = 800000;
    static constexpr std::uint64_t kWorkPerRestart = 16;
    static constexpr std::uint64_t kWorkPerShotStep = 4;  // a time-stepped shot step (the event scheme's hand-over)

    // The pool the scheme on top hands contacts to (null: none). Set once, before the first advance.
    void set_pool(HandOffPool* pool) { pool_ = pool; }

    // --- Intervals between restart points (the scheme on top drives them) ---
    bool started() const { return started_; }
    // A new interval opens at now_s (absolute s): the next restart point is set, no work counted yet.
    void open_interval(double now_s);
    // Starts afresh from the state alone (see above), and sets the interval's work budget from what
    // that restart cost.
    void start_from(SimulationState& state);
    // The interval ends: the next advance() starts afresh (a restart point, or the state was edited).
    void close_interval() { started_ = false; }
    double next_restart_s() const { return next_restart_; }  // absolute s
    void set_work_budget(std::uint64_t units) { work_budget_ = units; }
    // Adds work done (work units) since the last restart point; once it reaches the budget, brings
    // the next restart point forward to the next point of the sync grid (returns true then). now_s:
    // absolute s.
    bool count_work(std::uint64_t units, double now_s);

    // Where an advance stopped (absolute s), and the point of the sync grid it was heading for.
    struct Stop {
        double stop_s = 0.0;
        double grid_s = 0.0;
    };
    // Processes the events (and the pool's steps) up to min(t_end_s, pause_at_s, now + kSyncInterval,
    // the next restart point) and leaves the state (positions, velocities) exact at that time. Where
    // it pauses does not change the run. The interval must have been started.
    Stop advance(SimulationState& state, double t_end_s, double pause_at_s, std::vector<ImpactRecord>& impacts);

    // Room for n shot, and new shot (emitted at the state's time) taken into the flights now.
    void fit_shots(std::size_t n);
    void take_new_shots(SimulationState& state, const std::vector<int>& shots);

    // Of the active shot, the share lying still (slower than still_speed, m/s) on a surface or on
    // another still shot (from the state alone), and the share the core has in sustained contact
    // or asleep.
    // (resting_fraction is 0 when the still shot are no more than share_that_matters of the active.)
    double resting_fraction(const SimulationState& state, double share_that_matters, double still_speed_m_per_s) const;
    bool still_more_than(double share) const;

    const StepStats& stats() const { return stats_; }
    StepStats& stats() { return stats_; }

    // --- What a pool reads of, and does to, the core's flights (times: the core's clock) ---
    const SimTime& epoch() const { return epoch_; }
    double absolute_seconds(double t) const;  // the core's clock (s) -> absolute s
    Vec3 position(int i, double t) const;     // exact centre of shot i at t, whatever its motion
    Vec3 velocity(int i, double t) const;
    Shot& shot(int i) { return shots_[static_cast<std::size_t>(i)]; }
    const Shot& shot(int i) const { return shots_[static_cast<std::size_t>(i)]; }
    bool active(int i) const { return shots_.size() > static_cast<std::size_t>(i) && active_[static_cast<std::size_t>(i)]; }
    std::size_t shot_slots() const { return shots_.size(); }
    PairPredictor& pairs() { return pairs_; }
    const PairPredictor& pairs() const { return pairs_; }
    const WallPredictor& walls() const { return walls_; }
    const Vec3& gravity() const { return g_; }
    double resting_speed() const { return resting_speed_; }  // m/s
    double impact_speed() const { return impact_speed_; }    // m/s
    bool keeps_contact_state() const { return contact_state_; }
    // support: unit normal of the surface a sustained shot rests on (zero: none).
    void set_flight(int i, const Vec3& p, const Vec3& v, double t, Motion motion, const Vec3& support = Vec3::Zero());
    void predict_wall(int i, double t);
    void renew_box(int i, double t);
    void schedule(int i);
    void unschedule(int i);                    // no event for shot i until it is scheduled again
    void pairs_and_schedule(int i, double t);  // the pair predictor, then the pile or the queue
    void lose(int i, double t, SimulationState& state, bool non_finite);

private:
    void start(SimulationState& state);
    // Work done so far, weighted by what it costs: a shot-shot time-of-impact test is one unit, an
    // event or a shot x component prediction four. Events alone were a poor clock: in a dense load
    // (3072 shot of 2 mm) an event tests ~37 neighbour pairs and costs ~9 us, against ~1 us for a
    // lone small shot, and restart points came 1.5 s of wall time apart. Only differences are
    // used, so the counters' values before a resume do not matter. A member's step in a pool is one.
    std::uint64_t work_units() const {
        return 4 * (stats_.events + stats_.mesh_predictions) + stats_.pair_tests + stats_.soft_member_steps;
    }
    static double next_multiple(double t_s, double step_s);  // the first multiple of step_s after t_s
    double since_epoch(double t_s) const;                    // absolute s -> the core's clock (s)
    void process(int i, SimulationState& state, std::vector<ImpactRecord>& impacts);
    void predict(int i, double t);  // wall, box and pairs
    double key(const Shot& s) const;
    // A shot of radius R (m) centred at p touches a static surface.
    bool touches_surface(const Vec3& p, double R) const;

    // event_collisions.cpp
    void collide_wall(int i, double t, SimulationState& state, std::vector<ImpactRecord>& impacts);
    void collide_pair(int i, int j, double t, SimulationState& state, std::vector<ImpactRecord>& impacts);
    void start_ride(int i, double t, const WallEvent& w, const Vec3& p, const Vec3& v_after);
    void launch(int i, double t, SimulationState& state);
    // A touch without approach (v_kept: the velocity with the approach removed): sustained contact
    // if the surface presses the shot, else a graze that flies on.
    void touch(int i, double t, const WallEvent& w, const Vec3& p, const Vec3& v_kept);
    void substep(int i, double t, SimulationState& state, std::vector<ImpactRecord>& impacts);
    void collect(int i, SimulationState& state, std::size_t sink);  // entered sink `sink`: taken out, counted
    void retire(int i, SimulationState& state);                     // out of the run (lost or collected)
    // Wakes the sleeping shot touching shot i, and those touching them (a pile wakes as a whole).
    void wake_neighbours(int i, double t);

    // Whether `contacts` holds a contact of shot i.
    static bool has_contacts(const ContactStates& contacts, int i) {
        const auto it = contacts.entries().lower_bound({i, -1});
        return it != contacts.entries().end() && it->first.first == i;
    }

    std::shared_ptr<const Model> model_;
    HandOffPool* pool_ = nullptr;
    StepStats stats_;
    bool started_ = false;
    double next_restart_ = 0.0;  // s (absolute), the next restart point
    // The core's clock: every time below (flights, events, rides) is seconds since epoch_, the
    // state's time at the last restart point.
    SimTime epoch_;
    std::uint64_t work_since_restart_ = 0;
    std::uint64_t work_budget_ = 0;   // work units between restart points, at most (then the next grid point)
    std::uint64_t work_counted_ = 0;  // work_units() already counted
    double same_time_ = -1.0;         // s, the time of the latest event, and how many came at it (forced progress)
    std::uint64_t at_same_time_ = 0;
    std::vector<Shot> shots_;
    std::vector<unsigned char> active_;
    EventQueue queue_;
    PairPredictor pairs_;                  // neighbours by flight box, their first contacts
    std::vector<int> neighbours_;          // scratch of wake_neighbours
    std::vector<int> wake_stack_;          // scratch of wake_neighbours: shot whose neighbours to wake
    std::vector<int> woken_;               // scratch of wake_neighbours: shot woken so far
    WallPredictor walls_;                  // where a flight first meets a surface
    SustainedContact sustained_;           // the ends of sustained-contact substeps
    bool contact_state_ = false;           // a law keeps state per contact (SimulationState::contacts)
    std::vector<double> contact_scratch_;  // an instantaneous contact's state (zeros)

    double R_ = 0.0;                      // m, the smallest shot radius (scales the scheme's tolerances and windows)
    double R_max_ = 0.0;                  // m, the largest (how far a neighbour's centre can be)
    Vec3 g_ = Vec3::Zero();               // m/s2
    double resting_speed_ = 0.0;          // m/s, what gravity adds in two substeps: slower is still (sleep), a slower rebound is none
    double impact_speed_ = 0.0;           // m/s, Model::impact_speed_m_per_s: slower contacts are no impacts (sustained contact)
    double substep_ = 0.0;                // s, sustained-contact substep
    double box_travel_ = 0.0;             // m, how far a flight box reaches along the path
    std::uint64_t unresolved_ = 0;        // searches that ran out of iterations, added to the health at sync
    std::uint64_t search_fallbacks_ = 0;  // flights moved to substeps by the search fallback, added at sync
    SearchFallback first_fallback_;       // the first of them since the last sync (time_s < 0: none)
    std::uint64_t events_since_sync_ = 0;
};

}  // namespace peensim
