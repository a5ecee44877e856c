// The soft scheme's contacts (`accuracy.scheme: soft`): every shot in soft-sphere contact, and every
// shot that touches one of them, is a member of this pool and is integrated with the others on
// one clock, in steps chosen from the Hertz contact time; every other shot flies its exact parabola
// in the event-driven scheme, which hands a shot to the pool at the exact time it touches a
// surface or another shot, and takes it back when it leaves. Cost follows the contacts' duration,
// not the number of shot times the run's steps.
//
// The step (kick-drift-kick, as LIGGGHTS's nve/sphere velocity Verlet, but for the normal
// forces): half a kick, a drift, the contacts at the step's end (its node), the second half kick;
// the same for the spin, with the moment of inertia 2/5 m R^2 of a solid sphere. The point forces
// (gravity; Mindlin's tangential springs, advanced by the half-step slip, damped at the node
// velocities the last node predicts) kick as in Verlet, with their value at the node. Each
// contact's normal force (Hertz with its damping: the pair's law, contact/hertz_mindlin.h) kicks
// with its impulse over the half step, weighted 1 - |s|/h, integrated along the contact's path
// from the node (engine/soft/contact_impulse.h): the kick that puts the next node on the true
// path, right where a contact begins or ends inside a step, where Verlet's kick (the force at the
// node) gives each contact an energy error of either sign depending on where in the step it ends.
// Every pair of a member and a surface or another member within kNearMargin R at a node
// (overlapping or not) has a path, so a contact about to begin, or just ended, gets its share of
// the half steps around the node. The node velocities the paths start from are those the last
// node's paths predict (their impulses over the step, weighted the other way); both half steps
// around a node are integrated along the one path (so their errors cancel to a higher order).
// Its length: the smallest, over the contacts (and the gaps that may close within about a step),
// of the Hertz contact time at the speed that carries the contact's energy now, divided by
// `accuracy.soft_steps_per_contact` (the rule and its error: docs/design.md, "Soft-sphere contacts"). A
// vibrating or turning component is at its exact pose at every node.
//
// Who is a member: a shot joins when the scheme finds its exact touch (an impact, or any touch on a
// moving surface), or when a shot outside the pool would overlap a member by the end of the next
// step (found by the exact time of impact against the member's path; the pool steps exactly to that
// time first). It leaves to free flight after a whole step without any contact; and a group of
// members in contact whose contacts are all slow (none carries the energy of an approach at the
// impact line, `accuracy.impact_speed`, and each has lasted kSlowAge) leaves to rigid sustained
// contact (resting, sliding, riding: the event scheme's), so that a load at rest never costs
// microsecond steps. The same line as the rigid schemes: below it contacts are rigid.
//
// Impacts: a contact from its first overlap to its separation is one impact (LIGGGHTS's episode)
// if its approach speed at the start was at least the impact line: counted and, on a logged
// component, recorded when it ends, with the time, point and approach of its start and the
// rebound of its end. The approach speed is the normal speed that carries the contact's energy
// when it is first seen: sqrt(v_n^2 + 2 U / m*), U the elastic energy already in its overlap.
#pragma once

#include <limits>
#include <memory>
#include <vector>

#include "common/sim_time.h"
#include "contact/hertz_mindlin.h"
#include "engine/event/wall_predictor.h"
#include "engine/impact_record.h"
#include "engine/simulation_state.h"
#include "engine/soft/contact_impulse.h"
#include "engine/soft/surface_patch.h"
#include "engine/soft_contact.h"
#include "engine/step_stats.h"
#include "kernels/trajectory.h"
#include "model/model.h"

namespace peensim {

// What the pool reads of, and tells, the scheme around it: the shot outside the pool.
class SoftSurroundings {
public:
    virtual ~SoftSurroundings() = default;
    // The shot whose neighbour boxes overlap [lo, hi] (m, world), members among them.
    virtual void shots_in_box(const Vec3& lo, const Vec3& hi, std::vector<int>& out) const = 0;
    // A member's neighbour box (m, world): a shot whose own box comes to overlap it is offered to
    // the pool as a candidate (add_candidate).
    virtual void set_box(int shot, const Vec3& lo, const Vec3& hi) = 0;
    // A shot outside the pool: its path, exact from path.t0 (its last event) up to its next event
    // (its velocity with no acceleration if it rides or rests); false if it is not active.
    virtual bool path_of(int shot, double t, Trajectory& out) const = 0;
    // The pool took a shot in at time t (s, the scheme's clock): the scheme stops predicting it.
    virtual void joined(int shot, double t) = 0;
    // A member's centre and velocity after a step, at time t (the scheme's record of it, which
    // its other parts read while the shot is a member).
    virtual void moved(int shot, const Vec3& p, const Vec3& v, double t) = 0;
};

// A member that left the pool at the pool's time: to fly, to rigid sustained contact on `support`,
// or lost (its state stopped being a number).
struct SoftExit {
    enum class To : unsigned char { flight, rest, lost };
    int shot = -1;
    To to = To::flight;
    Vec3 position_m = Vec3::Zero();
    Vec3 velocity_m_per_s = Vec3::Zero();
    Vec3 support = Vec3::Zero();  // unit, the contact normal gravity presses on most (rest)
};

class SoftPool {
public:
    SoftPool(std::shared_ptr<const Model> model, const WallPredictor& walls);

    // Empty, its clock restarted at `epoch` (absolute): every time in or out is seconds since it.
    void reset(const SimTime& epoch, std::size_t shot_count);
    void grow(std::size_t shot_count);  // room for more shot (a source emitted)

    bool empty() const { return members_.empty(); }
    bool contains(int shot) const {
        return static_cast<std::size_t>(shot) < member_of_.size() && member_of_[static_cast<std::size_t>(shot)] >= 0;
    }
    std::size_t size() const { return members_.size(); }
    double time() const { return t_; }  // s, the scheme's clock
    // The end of the next step (s): the pool steps when nothing outside it happens before.
    double next_step_end() const;

    // Takes a shot in at time t (>= time(); the pool first steps exactly there) with its centre p,
    // velocity v and spin w there; approach_m_per_s and law: the touch that brings it (its speed
    // sets the first step), law null for a shot offered as a candidate.
    void join(int shot, double t, const Vec3& p, const Vec3& v, const Vec3& w, double approach_m_per_s, const contact::SoftLaw* law,
              SoftSurroundings& around, SimulationState& state, std::vector<ImpactRecord>& impacts, std::vector<SoftExit>& exits,
              StepStats& stats);
    // A shot outside the pool whose neighbour box overlaps member `member`'s.
    void add_candidate(int member, int shot);

    // One step (or, when a shot outside would touch a member within it, exactly up to that touch,
    // where the shot joins). Members that leave are appended to `exits`.
    void step(SoftSurroundings& around, SimulationState& state, std::vector<ImpactRecord>& impacts, std::vector<SoftExit>& exits,
              StepStats& stats);
    // Steps exactly to t (>= time()): a restart point, or a touch of the scheme around (a shot
    // outside that touches a member before t joins at its touch on the way).
    void step_to(double t, SoftSurroundings& around, SimulationState& state, std::vector<ImpactRecord>& impacts,
                 std::vector<SoftExit>& exits, StepStats& stats);

    // A member's centre, velocity and spin at t in [time(), next_step_end()] (the last step's
    // accelerations carried on: for the state a caller sees between steps).
    Vec3 position(int shot, double t) const;
    Vec3 velocity(int shot, double t) const;
    Vec3 spin(int shot) const;

    // The contacts in progress into the state (and every member's spin), in the order a restore reads.
    void save(SimulationState& state) const;
    // At a restart point: the members and contacts the state holds, at the pool's time (reset first).
    // Returns the members (the scheme marks them).
    const std::vector<int>& restore(SoftSurroundings& around, SimulationState& state, std::vector<ImpactRecord>& impacts,
                                    std::vector<SoftExit>& exits, StepStats& stats);

    // s: a slow contact leaves to rigid sustained contact only once it has lasted this long (a
    // slow landing on a plate that accelerates into the shot turns into a loaded contact first).
    static constexpr double kSlowAge = 20e-6;
    // of R: how far a member moves from where its triangles and neighbours were gathered before
    // they are gathered again.
    static constexpr double kGatherMargin = 0.25;
    // Members up to which every pair is tested for contact (beyond, a sweep along x).
    static constexpr std::size_t kAllPairsUpTo = 12;
    // of R: a member and a surface or another member this close at a node have a path (a gap
    // that may close within the next step, a contact that just ended); well beyond what two
    // members close in a step (40 m/s over a 1 us step is 0.04 R of a 1 mm shot), and within
    // kGatherMargin (the gathered triangles cover it).
    static constexpr double kNearMargin = 0.1;

private:
    // A contact in progress.
    struct Live {
        SoftContact c;
        int a = -1, b = -1;  // member slots of c.shot and c.partner (b: -1 for a component)
        contact::SoftPair pair;
        double delta_m = 0.0;         // m, overlap at the last evaluation
        double step_s = 0.0;          // s, the step this contact asks for now
        double energy_j = 0.0;        // J, its normal kinetic plus elastic energy now
        double start_energy_j = 0.0;  // J, ... when it began (a contact left to itself only loses energy)
        double start_step_s = 0.0;    // s, the step that energy asks for
        bool lively = false;          // carries at least the impact line's energy, or is younger than kSlowAge
        bool deep = false;            // counted once as a deep penetration
        Vec3 point_m = Vec3::Zero();  // m, world: the contact point now (on the surface)
    };
    // A member and a surface or another member within kNearMargin R at the last node: the path
    // along which the half kicks integrate its normal force (a superset of the live contacts).
    struct Path {
        int a = -1, b = -1;           // member slots of shot and partner (b: -1 for a component)
        int shot = -1, partner = -1;  // shot (partner: -1 for a component)
        int component = -1;           // -1 between two shot
        int live = -1;                // its contact in live_ while they overlap at the node, else -1
        contact::SoftPair pair;
        ContactPath path;
        Vec3 point_m = Vec3::Zero();  // m, world: the surface point nearest the centre (a component's)
        double distance_m = 0.0;      // m, centre to centre (two shot) or to that point
        double force_n = 0.0;         // N, its normal force at the node (0 apart)
    };
    // A shot outside the pool near a member, and until when it cannot reach it (s): it is looked
    // at again then, or when it flies anew (offered again), or when a member faster than
    // speed_bound (m/s) could close the gap sooner.
    struct Candidate {
        int shot = -1;
        double check_at = -std::numeric_limits<double>::infinity();
        double speed_bound = 0.0;
    };
    struct Member {
        int shot = -1;
        Vec3 p, v, w;               // m, m/s, rad/s
        Vec3 p_before, v_before;    // m, m/s: at the step's start
        Vec3 v_rate, w_rate;        // m/s, rad/s: at the node, as the last node predicts it (then the normal impulses)
        Vec3 a, alpha;              // m/s2, rad/s2: at the last node (every force at its value there)
        Vec3 f, tau;                // N, N m: every force at the node (scratch of the evaluation), torque
        Vec3 f_kick;                // N: gravity and the tangential forces at the last node (the half kicks' point forces)
        Vec3 impulse;               // N s: scratch, the normal impulses of a half kick
        Vec3 predicted;             // N s: the next node's normal impulses before it, as the last node's paths predict them
        bool touching = false;      // had a contact at the last evaluation
        bool was_touching = false;  // had one at the evaluation before (a whole step without: it flies)
        Vec3 box_centre;            // m, where its neighbour box and candidates were gathered
        bool box_set = false;
        std::vector<Candidate> candidates;  // shot outside the pool near it
        std::vector<SurfacePatch> patches;  // per component
        std::vector<int> contacts;          // indices into live_
    };

    int add_member(int shot, const Vec3& p, const Vec3& v, const Vec3& w);
    // One step up to t_end (s), or exactly up to the touch of a shot outside within it, which joins there.
    void advance(double t_end, SoftSurroundings& around, SimulationState& state, std::vector<ImpactRecord>& impacts,
                 std::vector<SoftExit>& exits, StepStats& stats);
    void remove_member(int slot);
    // One step up to t_end (s, the scheme's clock; the pool's time is then exactly t_end): the
    // first half kick, the drift, and evaluate() at the end.
    void integrate(double t_end, SoftSurroundings& around, SimulationState& state, std::vector<ImpactRecord>& impacts, StepStats& stats);
    // Contacts and forces at the members' current positions, the node at time t (s), after a step
    // of dt (s) whose second half kick it gives (the springs advanced by dt; 0: a look at the node
    // velocities, nothing advanced); contacts no longer found end (their impact records).
    void evaluate(double t, double dt, SimulationState& state, std::vector<ImpactRecord>& impacts, StepStats& stats);
    void wall_contacts(int m, double t, double spring_dt, SimulationState& state);
    void shot_contacts(double t, double spring_dt);
    // Every path's rate and normal force from the members' v_rate, the members' accelerations a
    // from those forces, and every path's outer acceleration.
    void normal_forces();
    // Every path's NodePath (followed up to the longer of dt_before and dt_after, s), and the
    // normal impulses of the half step dt_before before the node (v_rate becomes the node
    // velocity they give; 0: none).
    void normal_impulses(double dt_before, double dt_after);
    // A path's rate and force at the node from its members' v_rate (rate_only), or its turn and
    // outer acceleration from their accelerations a.
    void shape(Path& k, bool rate_only) const;
    // The paths of a member that just joined, at its touch (its half step ahead needs them).
    void look_around(int m);
    // Components and their surfaces' motion at time t (s).
    void set_poses(double t);
    // m/s2, the acceleration of component c's material point at q (m, world) at the evaluation's time.
    Vec3 surface_acceleration(std::size_t c, const Vec3& q) const;
    // A contact found now: the one in progress (`before`, an index into live_) or a new one from
    // `key` beginning at approach_now (m/s). Its index in next_live_; spring_step: how long (s) its
    // spring slipped in this step.
    int continue_or_begin(int before, const SoftContact& key, double t, double spring_dt, double approach_now, double& spring_step);
    void end_contact(const Live& l, double t, SimulationState& state, std::vector<ImpactRecord>& impacts);
    void leave(SimulationState& state, std::vector<ImpactRecord>& impacts, std::vector<SoftExit>& exits, StepStats& stats);
    void renew_box(int m, SoftSurroundings& around);
    // The earliest touch within [t_, t_end] of a shot outside with a member: its time, or +inf.
    double first_join(double t_end, SoftSurroundings& around, int& shot, StepStats& stats);
    double step_for_contact(const contact::SoftPair& p, double energy_j) const;  // s
    // m/s, the velocity of component c's material point at q (m, world) at the evaluation's time.
    Vec3 surface_velocity(std::size_t c, const Vec3& q) const;
    // A contact's energy, wanted step and liveliness now, from its overlap and closing rate (m/s).
    void settle_step(Live& l, double rate, double t) const;
    void report(SoftSurroundings& around);  // every member's state to the scheme

    std::shared_ptr<const Model> model_;
    const WallPredictor& walls_;
    SimTime epoch_;
    double t_ = 0.0;        // s, the pool's clock (the scheme's)
    double dt_ = 0.0;       // s, the next step
    double last_dt_ = 0.0;  // s, the step just taken
    double R_ = 0.0;        // m
    double mass_ = 0.0;     // kg
    double inertia_ = 0.0;  // kg m2, 2/5 m R^2
    Vec3 g_ = Vec3::Zero();
    double line_speed_ = 0.0;  // m/s, the impact line
    double steps_per_contact_ = 40.0;
    std::vector<Member> members_;
    std::vector<Member> spare_;   // retired members' records, reused by the next to join
    std::vector<int> member_of_;  // per shot: its slot in members_, -1 outside the pool
    std::vector<Live> live_, next_live_;
    std::vector<Live> ended_;  // scratch: the contacts that ended at the node (recorded once its velocities are known)
    std::vector<Path> paths_;  // at the last node
    // Per path: the path as its normal force is integrated, both half steps round the node.
    std::vector<NodePath> node_paths_;
    std::vector<Pose> poses_;  // per component, at the evaluation's time (a still one's set once)
    // Per component, at the evaluation's time: a vibrating one's (uniform) surface velocity (m/s).
    std::vector<Vec3> sliding_;
    std::vector<Vec3> shaking_;              // ... and its acceleration (m/s2)
    std::vector<Vec3> reach_lo_, reach_hi_;  // m, world, per component: a centre outside them touches nothing of it
    std::vector<Vec3> velocities_scratch_;
    std::vector<SurfaceOverlap> overlaps_;  // scratch
    std::vector<int> order_;                // scratch: members by x
    std::vector<int> neighbours_;           // scratch
    std::vector<int> parent_;               // scratch: union-find over members
    std::vector<unsigned char> lively_;     // scratch: per group root, a lively contact
    std::vector<unsigned char> leaving_;    // scratch: per member, 0 stays, 1 flies, 2 rests, 3 lost
    std::vector<unsigned char> continued_;  // scratch: per contact of live_, found again
    std::vector<int> restored_;             // restore()'s answer
    double pending_step_ = 0.0;             // s, the first step a touch asked for (0: none)
};

}  // namespace peensim
