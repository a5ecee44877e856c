#include "engine/soft/soft_stepping.h"

#include <algorithm>
#include <limits>

#include "common/float_limits.h"

namespace peensim {

SoftStepping::SoftStepping(std::shared_ptr<const Model> model) : model_(model), core_(model), pool_(std::move(model), core_.walls()) {
    core_.set_pool(this);
}

SoftStepping::~SoftStepping() = default;

void SoftStepping::advance(SimulationState& state, double t_end_s, double pause_at_s, std::vector<ImpactRecord>& impacts) {
    const double now_s = state.time.seconds();
    if (!(t_end_s > now_s)) return;
    if (!core_.started()) {
        core_.open_interval(now_s);
        core_.start_from(state);
    }
    core_.advance(state, t_end_s, pause_at_s, impacts);
}

void SoftStepping::shots_added(SimulationState& state, const std::vector<int>& shots) {
    core_.fit_shots(state.shots.size());
    // Between restart points nothing is kept that a new shot could upset.
    if (!core_.started()) return;
    core_.take_new_shots(state, shots);
}

// ---------------------------------------------------------------------------------------------
// What the pool takes

bool SoftStepping::take_wall_contact(int shot, double t, const Vec3& p, const Vec3& v, double approach, const Component& comp,
                                     const WallEvent& w, SimulationState& state, std::vector<ImpactRecord>& impacts) {
    // An impact, or a touch on a moving surface that approaches or that the surface presses (a
    // landing on the vibrating plate), is a soft contact, integrated by the pool.
    const bool soft =
        contact::is_impact(approach, core_.impact_speed()) ||
        (comp.kinematics.moves() && (approach > core_.resting_speed() || (w.surface_acceleration - core_.gravity()).dot(w.normal) > 0.0));
    if (!soft) return false;
    to_pool(shot, t, p, v, std::max(0.0, approach), comp.law->soft(), state, impacts);
    return true;
}

bool SoftStepping::take_pair_contact(int i, int j, double t, const Vec3& v_i, const Vec3& v_j, double approach, SimulationState& state,
                                     std::vector<ImpactRecord>& impacts) {
    if (!contact::is_impact(approach, core_.impact_speed())) return false;
    // Both shot are the pool's from their touch (positions as they are: a soft contact's overlap
    // is its physics).
    const Vec3 p_i = core_.position(i, t), p_j = core_.position(j, t);
    to_pool(i, t, p_i, v_i, approach, model_->shot_shot_law->soft(), state, impacts);
    to_pool(j, t, p_j, v_j, approach, model_->shot_shot_law->soft(), state, impacts);
    return true;
}

void SoftStepping::predicted(int shot, const std::vector<int>& members) {
    for (const int member : members) pool_.add_candidate(member, shot);
}

void SoftStepping::to_pool(int i, double t, const Vec3& p, const Vec3& v, double approach, const contact::SoftLaw* law,
                           SimulationState& state, std::vector<ImpactRecord>& impacts) {
    if (core_.keeps_contact_state()) state.contacts.end_all(i);
    pool_.join(i, t, p, v, state.shots.spin(static_cast<std::size_t>(i)), approach, law, *this, state, impacts, exits_, core_.stats());
    take_exits(state);
}

// ---------------------------------------------------------------------------------------------
// The pool's steps and restart points

double SoftStepping::step(SimulationState& state, std::vector<ImpactRecord>& impacts) {
    pool_.step(*this, state, impacts, exits_, core_.stats());
    take_exits(state);
    return pool_.time();
}

void SoftStepping::finish_interval(double t, SimulationState& state, std::vector<ImpactRecord>& impacts) {
    pool_.step_to(t, *this, state, impacts, exits_, core_.stats());
    take_exits(state);
    pool_.save(state);
}

void SoftStepping::restore(const SimTime& epoch, SimulationState& state) {
    std::vector<ImpactRecord> none;
    pool_.reset(epoch, core_.shot_slots());
    pool_.restore(*this, state, none, exits_, core_.stats());
}

void SoftStepping::take_exits(SimulationState& state) {
    if (exits_.empty()) return;
    const double t = pool_.time();
    // Each set up first, then predicted, so that their predictions see one another.
    for (const SoftExit& e : exits_) {
        const int i = e.shot;
        EventShot& s = core_.shot(i);
        switch (e.to) {
            case SoftExit::To::lost: break;
            case SoftExit::To::flight:
                s.in_flight = true;
                core_.set_flight(i, e.position_m, e.velocity_m_per_s, t, EventMotion::flying);
                break;
            case SoftExit::To::rest:
                s.in_flight = false;
                core_.set_flight(i, e.position_m, e.velocity_m_per_s, t, EventMotion::sustained, e.support);
                break;
        }
    }
    // Copied: a prediction may hand a shot to the pool again (and fill exits_ anew).
    std::vector<SoftExit> leaving;
    leaving.swap(exits_);
    for (const SoftExit& e : leaving) {
        if (e.to == SoftExit::To::lost) {
            core_.lose(e.shot, t, state, true);
            continue;
        }
        if (pool_.contains(e.shot)) continue;
        core_.predict_wall(e.shot, t);
        core_.renew_box(e.shot, t);
        core_.shot(e.shot).pair_time = kInf;
        core_.schedule(e.shot);
    }
    for (const SoftExit& e : leaving)
        if (e.to != SoftExit::To::lost && !pool_.contains(e.shot)) core_.pairs_and_schedule(e.shot, t);
    leaving.clear();
    if (exits_.empty()) leaving.swap(exits_);  // keep the capacity
}

// ---------------------------------------------------------------------------------------------
// SoftSurroundings

void SoftStepping::set_box(int shot, const Vec3& lo, const Vec3& hi) {
    EventShot& s = core_.shot(shot);
    s.box_lo = lo;
    s.box_hi = hi;
    s.box_until = kInf;
    core_.pairs().set_box(shot, lo, hi);
}

bool SoftStepping::path_of(int shot, double t, Trajectory& out) const {
    if (!core_.active(shot)) return false;
    const EventShot& s = core_.shot(shot);
    if (s.motion == EventMotion::riding) {
        out = Trajectory{core_.position(shot, t), core_.velocity(shot, t), Vec3::Zero(), t};
        return true;
    }
    out = s.path;
    return true;
}

void SoftStepping::joined(int shot, double t) {
    EventShot& s = core_.shot(shot);
    s.motion = EventMotion::pooled;
    ++s.version;  // pair events predicted against its flight are stale
    s.wall = WallEvent{};
    s.wall.time = kInf;
    s.pair_time = kInf;
    s.partner = -1;
    s.in_flight = false;
    s.path.t0 = t;
    core_.unschedule(shot);
}

void SoftStepping::moved(int shot, const Vec3& p, const Vec3& v, double t) { core_.shot(shot).path = Trajectory{p, v, core_.gravity(), t}; }

}  // namespace peensim
