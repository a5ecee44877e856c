// Event-driven stepping (`accuracy.scheme: event`): every shot flies its exact parabola (eq. 1)
// to its next collision, found exactly, and the run jumps from one collision to the next. Cost
// follows the number of collisions, not of time steps, and there is no step to alias the plate.
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
#pragma once

#include <memory>
#include <vector>

#include "collision/mesh_collider.h"
#include "engine/event/event_queue.h"
#include "engine/event/pair_predictor.h"
#include "engine/event/shot_motion.h"
#include "engine/event/shot_record.h"
#include "engine/event/sonotrode_face.h"
#include "engine/event/sustained_contact.h"
#include "engine/event/wall_event.h"
#include "engine/event/wall_predictor.h"
#include "engine/soft/soft_pool.h"
#include "engine/stepper.h"
#include "kernels/trajectory.h"
#include "model/model.h"

namespace peensim {

// The soft scheme (`accuracy.scheme: soft`) is this scheme with a SoftPool: a touch that is an
// impact (or any touch on a moving surface) hands the shot to the pool, which integrates its
// soft-sphere contacts with the others' and hands it back when it leaves; the pool's steps take
// their turn with the events in time order.
class EventStepping final : public Stepper, private SoftSurroundings {
public:
    explicit EventStepping(std::shared_ptr<const Model> model);
    ~EventStepping() override;

    std::string_view name() const override { return soft_ ? "soft" : "event"; }
    // Processes the events up to min(t_end_s, pause_at_s, now + kSyncInterval) and leaves the
    // state (positions, velocities) exact at that time. Where it pauses does not change the run.
    void advance(SimulationState& state, double t_end_s, double pause_at_s, std::vector<ImpactRecord>& impacts) override;
    // Its own work, plus the time stepping's of the intervals handed over.
    const StepStats& stats() const override;
    // Every kRestartInterval of simulated time the scheme starts afresh from the state alone (every
    // flight re-predicted, modes and neighbour tree rebuilt), exactly as a run resumed from a
    // checkpoint of that state does: so a resumed run equals the uninterrupted one, byte for byte.
    // Restart points come every kRestartInterval of simulated time, and at the next point of the
    // sync grid after every work budget (so at least every few tenths of a second of wall time:
    // checkpoints and interrupts wait for one).
    bool at_restart_point() const override { return !started_; }
    // Starts afresh from the edited state at the next advance(), as at a restart point.
    void state_changed() override;
    // Predicts the new shot's flights at once (the scheme stopped at their emission time).
    void shots_added(SimulationState& state, const std::vector<int>& shots) override;
    static constexpr double kRestartInterval = 0.1;  // s
    // The search fallback: a flight whose contact search runs out of iterations this many times in a
    // row (each kMaxAdvancement conservative-advancement steps within a hair of a moving surface,
    // gaining almost no time) goes on in sustained-contact substeps, which always advance time by
    // a substep; counted in HealthCounters::search_fallbacks. The net under "simulated time always
    // advances" (a blade turning at 1000 rpm once stalled so); rare: nozzle-gear 7 times in 30 s,
    // a shot pressed by a turning surface chattering in arcs of about 1 um (README, health counters).
    static constexpr int kMaxResumedSearches = 4;

    // Simulated time (s) one advance() covers at most: it stops on a grid of this spacing (absolute
    // multiples), where the state is brought up to date for progress, checkpoints and interrupts.
    static constexpr double kSyncInterval = 1e-3;
    // Work between restart points, in work units (work_units(): ~0.25 us of wall time each): at
    // least kMinWorkBudget, and kWorkPerRestart times what the last restart cost (re-predicting
    // every shot), so restarts take at most ~1/16 of the run.
    static constexpr std::uint64_t kMinWorkBudget = 800000;
    static constexpr std::uint64_t kWorkPerRestart = 16;

private:
    using Motion = EventMotion;
    using Shot = EventShot;

    void start(SimulationState& state);
    // Work done so far, weighted by what it costs: a shot-shot time-of-impact test is one unit, an
    // event or a shot x component prediction four. Events alone were a poor clock: in a dense load
    // (3072 shot of 2 mm) an event tests ~37 neighbour pairs and costs ~9 us, against ~1 us for a
    // lone small shot, and restart points came 1.5 s of wall time apart. Only differences are
    // used, so the counters' values before a resume do not matter.
    // A member's step in the soft pool is one unit.
    std::uint64_t work_units() const {
        return 4 * (stats_.events + stats_.mesh_predictions) + stats_.pair_tests + stats_.soft_member_steps;
    }
    static constexpr std::uint64_t kWorkPerShotStep = 4;  // a time-stepped shot step (hand-over)
    // Adds work done (work units) since the last restart point; once it
    // reaches the budget, brings the next restart point forward to the next point of the sync grid
    // (returns true then). now_s: absolute s.
    bool count_work(std::uint64_t units, double now_s);
    static double next_multiple(double t_s, double step_s);  // the first multiple of step_s after t_s
    double since_epoch(double t_s) const;                    // absolute s -> the scheme's clock (s)
    double absolute_seconds(double t) const;                 // the scheme's clock (s) -> absolute s
    void process(int i, SimulationState& state, std::vector<ImpactRecord>& impacts);
    void predict(int i, double t);  // wall, box and pairs
    void predict_wall(int i, double t);
    void pairs_and_schedule(int i, double t);  // the pair predictor, then the pile or the queue
    void renew_box(int i, double t);
    void schedule(int i);
    double key(const Shot& s) const;
    // A component that does not move within R (plus the contact slack) of p.
    // A shot of radius R (m) centred at p touches a static surface.
    bool touches_surface(const Vec3& p, double R) const;
    double resting_fraction(const SimulationState& state) const;  // of the active shot, still on a surface

    void collide_wall(int i, double t, SimulationState& state, std::vector<ImpactRecord>& impacts);
    void collide_pair(int i, int j, double t, SimulationState& state, std::vector<ImpactRecord>& impacts);
    void start_ride(int i, double t, const WallEvent& w, const Vec3& p, const Vec3& v_after);
    void launch(int i, double t, SimulationState& state);
    // A touch without approach (v_kept: the velocity with the approach removed): sustained contact
    // if the surface presses the shot, else a graze that flies on.
    void touch(int i, double t, const WallEvent& w, const Vec3& p, const Vec3& v_kept);
    void substep(int i, double t, SimulationState& state, std::vector<ImpactRecord>& impacts);
    void lose(int i, double t, SimulationState& state, bool non_finite);
    void collect(int i, SimulationState& state, std::size_t sink);  // entered sink `sink`: taken out, counted
    void retire(int i, SimulationState& state);                     // out of the run (lost or collected)
    void fit_shots(std::size_t n);                                  // per-shot records for n shot
    // support: unit normal of the surface a sustained shot rests on (zero: none).
    void set_flight(int i, const Vec3& p, const Vec3& v, double t, Motion motion, const Vec3& support = Vec3::Zero());
    // Wakes the sleeping shot touching shot i, and those touching them (a pile wakes as a whole).
    void wake_neighbours(int i, double t);
    // The soft pool takes shot i in at t (its touch approaching at `approach`, m/s, with `law`).
    void to_pool(int i, double t, const Vec3& p, const Vec3& v, double approach, const contact::SoftLaw* law, SimulationState& state,
                 std::vector<ImpactRecord>& impacts);
    // The members that left the pool go on in this scheme (at the pool's time).
    void take_exits(SimulationState& state);
    // The pool members a prediction met are offered to the pool as shot i's neighbours.
    void offer_to_pool(int i);

    // SoftSurroundings: what the pool reads of, and tells, this scheme.
    void shots_in_box(const Vec3& lo, const Vec3& hi, std::vector<int>& out) const override { pairs_.overlapping(lo, hi, out); }
    void set_box(int shot, const Vec3& lo, const Vec3& hi) override;
    bool path_of(int shot, double t, Trajectory& out) const override;
    void joined(int shot, double t) override;
    void moved(int shot, const Vec3& p, const Vec3& v, double t) override;

    // Whether `contacts` holds a contact of shot i.
    static bool has_contacts(const ContactStates& contacts, int i) {
        const auto it = contacts.entries().lower_bound({i, -1});
        return it != contacts.entries().end() && it->first.first == i;
    }
    // Exact centre and velocity of shot i at time t, whatever its motion.
    Vec3 position(int i, double t) const;
    Vec3 velocity(int i, double t) const;

    std::shared_ptr<const Model> model_;
    StepStats stats_;
    mutable StepStats combined_;  // stats(): stats_ plus the handed-over time stepping's
    bool started_ = false;
    bool handed_over_ = false;            // this interval is time-stepped
    std::unique_ptr<Stepper> hand_over_;  // the scheme a load at rest is handed to (time stepping), built at the first hand-over
    double next_restart_ = 0.0;           // s (absolute), the next restart point
    // The scheme's clock: every time below (flights, events, rides) is seconds since epoch_, the
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
    std::unique_ptr<SoftPool> soft_;       // the soft scheme's contacts (null for the event scheme)
    std::vector<SoftExit> exits_;          // scratch: members that left the pool
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
