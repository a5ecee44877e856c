#include "engine/soft/soft_pool.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <tuple>

#include "common/float_limits.h"
#include "contact/contact_policy.h"
#include "kernels/sphere_pair_toi.h"

namespace peensim {

namespace {

constexpr double kMinStep = 1e-12;  // s, a step is never shorter (time always moves on)

// m/s, the normal approach speed of a contact first seen now at overlap delta_m (m), closing at
// rate_m_per_s (m/s): the approach at the step's start (approach_before, m/s) when it touched
// already then (a touch found exactly: the shot joined there), else the speed that carries the
// contact's energy now, its elastic energy included (LIGGGHTS's first contact frame, corrected).
double onset_speed(const contact::SoftPair& elastic, double gap_before_m, double approach_before, double rate_m_per_s, double delta_m) {
    if (gap_before_m <= 1e-9 * elastic.R_star_m) return std::max(0.0, approach_before);
    return std::sqrt(rate_m_per_s * rate_m_per_s + 2.0 * contact::soft_elastic_energy(elastic, delta_m) / elastic.m_star_kg);
}

}  // namespace

SoftPool::SoftPool(std::shared_ptr<const Model> model, const WallPredictor& walls) : model_(std::move(model)), walls_(walls) {
    const Model& m = *model_;
    // One size: the scene refuses a mix with the soft scheme (its Hertz-Mindlin pairs are built
    // for one radius and mass).
    if (m.has_size_mix()) throw std::logic_error("the soft scheme runs shot of one size");
    R_ = m.shot_sizes.front().radius_m;
    mass_ = m.shot_sizes.front().mass_kg;
    inertia_ = 0.4 * mass_ * R_ * R_;
    g_ = m.gravity_m_per_s2;
    line_speed_ = m.impact_speed_m_per_s;
    steps_per_contact_ = m.soft_steps_per_contact;
    poses_.resize(m.components.size());
    sliding_.assign(m.components.size(), Vec3::Zero());
    shaking_.assign(m.components.size(), Vec3::Zero());
    for (std::size_t c = 0; c < m.components.size(); ++c) {
        const Component& comp = m.components[c];
        poses_[c] = comp.kinematics.rest;
        // The component's bounds over its motion, grown by what a sphere and its gathering reach.
        const Vec3 grow = Vec3::Constant((1.0 + kGatherMargin) * R_);
        reach_lo_.push_back(comp.world_lo - grow);
        reach_hi_.push_back(comp.world_hi + grow);
    }
}

void SoftPool::reset(const SimTime& epoch, std::size_t shot_count) {
    epoch_ = epoch;
    t_ = 0.0;
    dt_ = 0.0;
    pending_step_ = 0.0;
    members_.clear();
    member_of_.assign(shot_count, -1);
    live_.clear();
    paths_.clear();
    node_paths_.clear();
}

void SoftPool::grow(std::size_t shot_count) {
    if (shot_count > member_of_.size()) member_of_.resize(shot_count, -1);
}

double SoftPool::next_step_end() const { return members_.empty() ? kInf : t_ + dt_; }

Vec3 SoftPool::surface_velocity(std::size_t c, const Vec3& q) const {
    const Kinematics& k = model_->components[c].kinematics;
    if (k.kind == Kinematics::Kind::rotating) return k.omega_rad_per_s * k.axis_direction.cross(q - k.axis_point_m);
    return sliding_[c];  // vibrating (the same everywhere), or still (zero)
}

double SoftPool::step_for_contact(const contact::SoftPair& p, double energy_j) const {
    const double v = std::max(line_speed_, std::sqrt(2.0 * std::max(0.0, energy_j) / p.m_star_kg));
    return std::max(kMinStep, contact::soft_contact_duration(p, v) / steps_per_contact_);
}

int SoftPool::add_member(int shot, const Vec3& p, const Vec3& v, const Vec3& w) {
    const int slot = static_cast<int>(members_.size());
    // A retired member's record is reused, its lists' room with it: joining allocates nothing once warm.
    if (spare_.empty()) {
        members_.emplace_back();
    } else {
        members_.push_back(std::move(spare_.back()));
        spare_.pop_back();
    }
    Member& M = members_.back();
    M.shot = shot;
    M.p = M.p_before = p;
    M.v = M.v_before = v;
    M.w = w;
    M.a = g_;
    M.alpha = Vec3::Zero();
    M.v_rate = v;
    M.w_rate = w;
    M.f = M.f_kick = mass_ * g_;
    M.tau = Vec3::Zero();
    M.impulse = Vec3::Zero();
    M.touching = M.was_touching = false;
    M.box_set = false;
    M.candidates.clear();
    M.contacts.clear();
    M.patches.resize(model_->components.size());
    for (SurfacePatch& s : M.patches) s.clear();
    member_of_[static_cast<std::size_t>(shot)] = slot;
    return slot;
}

void SoftPool::remove_member(int slot) {
    const int last = static_cast<int>(members_.size()) - 1;
    member_of_[static_cast<std::size_t>(members_[static_cast<std::size_t>(slot)].shot)] = -1;
    if (slot != last) {
        std::swap(members_[static_cast<std::size_t>(slot)], members_[static_cast<std::size_t>(last)]);
        member_of_[static_cast<std::size_t>(members_[static_cast<std::size_t>(slot)].shot)] = slot;
    }
    spare_.push_back(std::move(members_.back()));
    members_.pop_back();
}

void SoftPool::add_candidate(int member, int shot) {
    if (!contains(member) || contains(shot) || member == shot) return;
    std::vector<Candidate>& c = members_[static_cast<std::size_t>(member_of_[static_cast<std::size_t>(member)])].candidates;
    for (Candidate& k : c)
        if (k.shot == shot) {
            k.check_at = -kInf;  // it flies anew: looked at again
            return;
        }
    c.push_back({shot});
}

void SoftPool::renew_box(int m, SoftSurroundings& around) {
    Member& M = members_[static_cast<std::size_t>(m)];
    M.box_centre = M.p;
    M.box_set = true;
    // Every place the sphere can reach while its centre stays within the margin of here.
    const Vec3 reach = Vec3::Constant((1.0 + kGatherMargin) * R_ + 1e-9 * R_);
    around.set_box(M.shot, M.p - reach, M.p + reach);
    around.shots_in_box(M.p - reach, M.p + reach, neighbours_);
    M.candidates.clear();
    for (const int k : neighbours_)
        if (!contains(k)) M.candidates.push_back({k});
}

void SoftPool::report(SoftSurroundings& around) {
    for (const Member& M : members_) around.moved(M.shot, M.p, M.v, t_);
}

Vec3 SoftPool::position(int shot, double t) const {
    const Member& M = members_[static_cast<std::size_t>(member_of_[static_cast<std::size_t>(shot)])];
    const double u = t - t_;
    return M.p + u * M.v + (0.5 * u * u) * M.a;
}

Vec3 SoftPool::velocity(int shot, double t) const {
    const Member& M = members_[static_cast<std::size_t>(member_of_[static_cast<std::size_t>(shot)])];
    return M.v + (t - t_) * M.a;
}

Vec3 SoftPool::spin(int shot) const { return members_[static_cast<std::size_t>(member_of_[static_cast<std::size_t>(shot)])].w; }

// ---------------------------------------------------------------------------------------------
// Joining and stepping

void SoftPool::join(int shot, double t, const Vec3& p, const Vec3& v, const Vec3& w, double approach_m_per_s, const contact::SoftLaw* law,
                    SoftSurroundings& around, SimulationState& state, std::vector<ImpactRecord>& impacts, std::vector<SoftExit>& exits,
                    StepStats& stats) {
    if (!members_.empty() && t > t_) step_to(t, around, state, impacts, exits, stats);
    // It touched a member on the way there and joined then: the pool has it (and finds this
    // touch among its paths).
    if (contains(shot)) return;
    if (members_.empty()) t_ = t;
    const int slot = add_member(shot, p, v, w);
    around.joined(shot, t);
    ++stats.soft_joins;
    if (law != nullptr) {
        // The touch's own contact asks for its step before it is first seen.
        const contact::SoftPair pair = law->contact(approach_m_per_s);
        const double wanted = step_for_contact(pair, 0.5 * pair.m_star_kg * approach_m_per_s * approach_m_per_s);
        pending_step_ = pending_step_ > 0.0 ? std::min(pending_step_, wanted) : wanted;
    }
    if (pending_step_ > 0.0) dt_ = members_.size() == 1 || !(dt_ > 0.0) ? pending_step_ : std::min(dt_, pending_step_);
    if (!(dt_ > 0.0)) dt_ = step_for_contact(model_->shot_shot_law->soft()->contact(line_speed_), 0.0);
    look_around(slot);
    renew_box(slot, around);
}

double SoftPool::first_join(double t_end, SoftSurroundings& around, int& shot, StepStats& stats) {
    double best = kInf;
    shot = -1;
    // How fast a member may move until a candidate is looked at again: the fastest member now, and
    // what a moving surface can add to it (a plate or a part throws a shot at up to twice its speed).
    double speed_bound = 0.0;
    for (const Member& M : members_) speed_bound = std::max(speed_bound, M.v.norm());
    speed_bound += 2.0 * model_->peak_surface_speed_m_per_s;
    const double g = g_.norm();
    for (std::size_t m = 0; m < members_.size(); ++m) {
        if (!members_[m].box_set || (members_[m].p - members_[m].box_centre).norm() > kGatherMargin * R_)
            renew_box(static_cast<int>(m), around);
        Member& M = members_[m];
        const Trajectory pm{M.p, M.v, M.a, t_};
        std::vector<Candidate>& cands = M.candidates;
        for (std::size_t k = 0; k < cands.size();) {
            Candidate& c = cands[k];
            if (t_end < c.check_at && speed_bound <= c.speed_bound) {
                ++k;
                continue;
            }
            const int j = c.shot;
            Trajectory pj;
            if (contains(j) || !around.path_of(j, t_, pj)) {
                cands[k] = cands.back();
                cands.pop_back();
                continue;
            }
            ++k;
            const double tb = std::max(t_, pj.t0);
            if (tb > t_end) continue;
            const double gap = (pj.position(tb) - pm.position(tb)).norm() - 2.0 * R_;
            // Apart for a while: not looked at until the gap could have closed, at the candidate's
            // speed (gravity adding for up to a millisecond) and the members' bound.
            const double closing = pj.velocity(tb).norm() + g * 1e-3 + speed_bound;
            if (gap > 0.0 && gap > closing * (t_end - tb)) {
                c.check_at = tb + std::min(1e-3, gap / closing);
                c.speed_bound = speed_bound;
                continue;
            }
            ++stats.pair_tests;
            PairContact pc;
            const ToiStatus st = sphere_pair_toi(pj, R_, pm, R_, tb, t_end, pc);
            if (st == ToiStatus::miss) continue;
            const double when = st == ToiStatus::overlapping ? tb : pc.time;
            if (when < best || (when == best && j < shot)) {
                best = when;
                shot = j;
            }
        }
    }
    return best;
}

void SoftPool::step(SoftSurroundings& around, SimulationState& state, std::vector<ImpactRecord>& impacts, std::vector<SoftExit>& exits,
                    StepStats& stats) {
    if (members_.empty()) return;
    StageTimer timer(stats, Stage::soft_contacts);
    advance(t_ + dt_, around, state, impacts, exits, stats);
}

void SoftPool::step_to(double t, SoftSurroundings& around, SimulationState& state, std::vector<ImpactRecord>& impacts,
                       std::vector<SoftExit>& exits, StepStats& stats) {
    StageTimer timer(stats, Stage::soft_contacts);
    while (!members_.empty() && t_ < t) advance(std::min(t_ + dt_, t), around, state, impacts, exits, stats);
    if (members_.empty()) t_ = std::max(t_, t);
}

void SoftPool::advance(double t_end, SoftSurroundings& around, SimulationState& state, std::vector<ImpactRecord>& impacts,
                       std::vector<SoftExit>& exits, StepStats& stats) {
    int shot = -1;
    const double touch = first_join(t_end, around, shot, stats);
    if (!(touch <= t_end && shot >= 0)) {
        integrate(t_end, around, state, impacts, stats);
        leave(state, impacts, exits, stats);
        return;
    }
    // A shot outside reaches a member within this step: the pool steps exactly to its touch, where
    // it joins (its contact then starts at a node, at zero overlap). Nobody leaves there: the
    // member it touches may have just ended its other contacts, and must meet it in the pool
    // (the others leave at the next node).
    if (touch > t_) integrate(touch, around, state, impacts, stats);
    Trajectory path;
    if (!around.path_of(shot, touch, path)) return;
    const Vec3 p = path.position(touch), v = path.velocity(touch);
    // Its approach to the nearest member (the one it touches; the member's path there is the
    // parabola of its last node, so not exactly at contact distance): the contact's first step.
    double approach = 0.0, nearest = std::numeric_limits<double>::infinity();
    for (const Member& M : members_) {
        const Vec3 d = M.p - p;
        const double dist = d.norm();
        if (!(dist > 0.0) || !(dist < nearest)) continue;
        nearest = dist;
        approach = std::max(0.0, (v - M.v).dot(d / dist));
    }
    join(shot, touch, p, v, state.shots.spin(static_cast<std::size_t>(shot)), approach, model_->shot_shot_law->soft(), around, state,
         impacts, exits, stats);
}

void SoftPool::integrate(double t_end, SoftSurroundings& around, SimulationState& state, std::vector<ImpactRecord>& impacts,
                         StepStats& stats) {
    const double dt = t_end - t_;
    last_dt_ = dt;
    for (Member& M : members_) {
        M.p_before = M.p;
        M.v_before = M.v;
        M.predicted = Vec3::Zero();
    }
    // The first half kick: each contact's normal impulse over the half step ahead, along its path
    // from the node (exact where it begins or ends within the step), and the point forces.
    for (std::size_t i = 0; i < paths_.size(); ++i) {
        const Path& k = paths_[i];
        const HalfStepImpulse j = node_paths_[i].half_step(dt);
        Member& A = members_[static_cast<std::size_t>(k.a)];
        A.v += j.near / mass_;
        A.predicted += j.far;
        if (k.b < 0) continue;
        Member& B = members_[static_cast<std::size_t>(k.b)];
        B.v -= j.near / mass_;
        B.predicted -= j.far;
    }
    for (Member& M : members_) {
        M.v += (0.5 * dt / mass_) * M.f_kick;
        M.w += 0.5 * dt * M.alpha;
        M.p += dt * M.v;
    }
    // The step's end, on the scheme's clock: exactly the join's or the restart's time when it is one.
    // The evaluation there gives the velocities' second half kick.
    t_ = t_end;
    evaluate(t_, dt, state, impacts, stats);
    for (Member& M : members_) M.w += 0.5 * dt * M.alpha;
    ++stats.soft_steps;
    stats.soft_member_steps += members_.size();
    report(around);
}

// ---------------------------------------------------------------------------------------------
// Contacts and forces

void SoftPool::set_poses(double t) {
    const Model& m = *model_;
    for (std::size_t c = 0; c < m.components.size(); ++c) {
        const Kinematics& k = m.components[c].kinematics;
        if (!k.moves()) continue;
        if (k.kind == Kinematics::Kind::vibrating) {
            // All from one phase: the plate's offset, velocity and acceleration (a turning part's pose is a rotation).
            const double phase = 2.0 * M_PI * epoch_.cycle_fraction(k.frequency_hz, t) + k.phase_rad;
            const double sn = std::sin(phase), cs = std::cos(phase), w = k.angular_frequency();
            poses_[c] = {k.rest.rotation, k.rest.translation + k.axis * (k.amplitude_m * sn)};
            sliding_[c] = k.axis * (k.amplitude_m * w * cs);
            shaking_[c] = k.axis * (-k.amplitude_m * w * w * sn);
        } else {
            poses_[c] = k.pose(epoch_, t);
        }
    }
}

Vec3 SoftPool::surface_acceleration(std::size_t c, const Vec3& q) const {
    const Kinematics& k = model_->components[c].kinematics;
    if (k.kind == Kinematics::Kind::rotating) {
        const Vec3 spin = k.omega_rad_per_s * k.axis_direction;
        return spin.cross(spin.cross(q - k.axis_point_m));  // centripetal
    }
    return shaking_[c];  // vibrating (the same everywhere), or still (zero)
}

void SoftPool::evaluate(double t, double dt, SimulationState& state, std::vector<ImpactRecord>& impacts, StepStats& stats) {
    set_poses(t);
    for (Member& M : members_) {
        // The node velocities, first as the last node predicts them (its point forces, and its
        // paths' impulses over the half step before this node): the springs' damping takes these
        // (the half-step velocities, which the springs' slip takes, lag half a step); the normal
        // impulses along this node's paths correct them (normal_impulses).
        M.v_rate = dt > 0.0 ? Vec3(M.v + (0.5 * dt / mass_) * M.f_kick + M.predicted / mass_) : M.v;
        M.w_rate = M.w + 0.5 * dt * M.alpha;
        M.f_kick = mass_ * g_;
        M.tau = Vec3::Zero();
        M.touching = false;
        M.contacts.clear();
    }
    // Which contacts of the last evaluation go on (the members' lists index them).
    for (std::size_t k = 0; k < live_.size(); ++k) {
        Live& l = live_[k];
        l.a = member_of_[static_cast<std::size_t>(l.c.shot)];
        l.b = l.c.partner >= 0 ? member_of_[static_cast<std::size_t>(l.c.partner)] : -1;
        if (l.a >= 0) members_[static_cast<std::size_t>(l.a)].contacts.push_back(static_cast<int>(k));
    }
    continued_.assign(live_.size(), 0);
    next_live_.clear();
    paths_.clear();
    for (std::size_t k = 0; k < members_.size(); ++k) wall_contacts(static_cast<int>(k), t, dt, state);
    shot_contacts(t, dt);
    ended_.clear();
    for (std::size_t k = 0; k < live_.size(); ++k)
        if (!continued_[k]) ended_.push_back(live_[k]);
    std::swap(live_, next_live_);
    // The normal forces at the node, the paths' rates and outer accelerations.
    normal_forces();
    double step = kInf;
    for (const Path& k : paths_)
        if (k.live >= 0) settle_step(live_[static_cast<std::size_t>(k.live)], k.path.rate_m_per_s, t);
    for (Live& l : live_) {
        step = std::min(step, l.step_s);
        if (l.c.partner >= 0) {
            members_[static_cast<std::size_t>(l.a)].touching = true;
            members_[static_cast<std::size_t>(l.b)].touching = true;
        } else {
            members_[static_cast<std::size_t>(l.a)].touching = true;
        }
    }
    // A gap closing fast enough to open a contact within about a step asks for that contact's step
    // before it begins.
    const double ahead = 2.0 * std::min(step, dt_ > 0.0 ? dt_ : step);
    for (const Path& k : paths_) {
        if (k.live >= 0 || !(k.path.rate_m_per_s > 0.0) || !(k.path.overlap_m + k.path.rate_m_per_s * ahead > 0.0)) continue;
        step = std::min(step, step_for_contact(k.pair, 0.5 * k.pair.m_star_kg * k.path.rate_m_per_s * k.path.rate_m_per_s));
    }
    if (dt > 0.0) pending_step_ = 0.0;
    if (pending_step_ > 0.0) step = std::min(step, pending_step_);
    if (step < kInf) dt_ = step;
    // The second half kick (the normal impulses of the half step before the node along the
    // paths), and the next step's first, as the paths from the velocities predicted here give
    // them (one path both ways round a node keeps the errors of its two sides opposite).
    normal_impulses(dt, dt_);
    for (Member& M : members_) M.v = M.v_rate;
    // Contacts that ended are recorded with the velocities after them.
    for (const Live& l : ended_) end_contact(l, t, state, impacts);
    for (Member& M : members_) M.alpha = M.tau / inertia_;
    stats.soft_contact_evaluations += live_.size();
}

void SoftPool::shape(Path& k, bool rate_only) const {
    const Member& A = members_[static_cast<std::size_t>(k.a)];
    const auto c = static_cast<std::size_t>(k.component);
    const Vec3 other_v = k.b >= 0 ? members_[static_cast<std::size_t>(k.b)].v_rate : surface_velocity(c, k.point_m);
    const Vec3& n = k.path.normal;
    const Vec3 rel_v = A.v_rate - other_v;
    if (rate_only) {
        k.path.rate_m_per_s = -n.dot(rel_v);
        k.force_n = k.path.overlap_m > 0.0 ? contact::soft_normal_force(k.pair, k.path.overlap_m, k.path.rate_m_per_s) : 0.0;
        return;
    }
    const Vec3 other_a = k.b >= 0 ? members_[static_cast<std::size_t>(k.b)].a : surface_acceleration(c, k.point_m);
    const Vec3 rel_a = A.a - other_a;
    // What the contact's own normal force adds to d2 delta/dt2 (-F/m*) is taken out: the path
    // integrates it along the way (contact_impulse.h).
    const double own = k.force_n / k.pair.m_star_kg;
    if (k.b >= 0) {
        // Two shot: the line of centres turns as they pass, and bends the overlap's path
        // (|d|'' = n . d'' + |d'_t|^2 / |d|).
        const Vec3 slide = rel_v + k.path.rate_m_per_s * n;  // tangential relative velocity
        k.path.turn_per_s = slide / k.distance_m;
        k.path.outer_accel_m_per_s2 = -n.dot(rel_a) - slide.squaredNorm() / k.distance_m + own;
        return;
    }
    const Kinematics& kin = model_->components[c].kinematics;
    if (kin.kind == Kinematics::Kind::rotating && kin.omega_rad_per_s != 0.0) {
        // A face of a turning part: its normal turns with it (n' = omega x n), which adds to the
        // overlap's acceleration 2 n' . (v - v_q) and |n'|^2 times the centre's distance.
        const Vec3 turn = (kin.omega_rad_per_s * kin.axis_direction).cross(n);
        k.path.turn_per_s = turn;
        k.path.outer_accel_m_per_s2 = -n.dot(rel_a) - 2.0 * turn.dot(rel_v) + turn.squaredNorm() * k.distance_m + own;
        return;
    }
    k.path.turn_per_s = Vec3::Zero();
    k.path.outer_accel_m_per_s2 = -n.dot(rel_a) + own;
}

void SoftPool::normal_forces() {
    for (Member& M : members_) M.f = M.f_kick;
    // The rates from the velocities at the node, and the normal forces there (for the accelerations).
    for (Path& k : paths_) {
        shape(k, true);
        if (k.force_n == 0.0) continue;
        const Vec3 f = k.force_n * k.path.normal;
        members_[static_cast<std::size_t>(k.a)].f += f;
        if (k.b >= 0) members_[static_cast<std::size_t>(k.b)].f -= f;
    }
    for (Member& M : members_) {
        M.a = M.f / mass_;
        if (!std::isfinite(M.a.squaredNorm())) M.a = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    }
    // The paths' outer accelerations from those.
    for (Path& k : paths_) shape(k, false);
}

void SoftPool::normal_impulses(double dt_before, double dt_after) {
    for (Member& M : members_) M.impulse = Vec3::Zero();
    node_paths_.resize(paths_.size());
    for (std::size_t i = 0; i < paths_.size(); ++i) {
        const Path& k = paths_[i];
        node_paths_[i] = node_path(k.pair, k.path, dt_before, dt_after);
        if (!(dt_before > 0.0)) continue;
        const Vec3 j = node_paths_[i].half_step(-dt_before).near;
        members_[static_cast<std::size_t>(k.a)].impulse += j;
        if (k.b >= 0) members_[static_cast<std::size_t>(k.b)].impulse -= j;
    }
    if (!(dt_before > 0.0)) return;
    for (Member& M : members_) M.v_rate = M.v + (0.5 * dt_before / mass_) * M.f_kick + M.impulse / mass_;
}

void SoftPool::look_around(int m) {
    set_poses(t_);
    const Model& model = *model_;
    const std::size_t first = paths_.size();
    Member& M = members_[static_cast<std::size_t>(m)];
    const double reach_R = (1.0 + kNearMargin) * R_;
    for (std::size_t c = 0; c < model.components.size(); ++c) {
        if ((M.p.array() < reach_lo_[c].array()).any() || (M.p.array() > reach_hi_[c].array()).any()) continue;  // nowhere near
        const Component& comp = model.components[c];
        const Pose& pose = poses_[c];
        overlaps_.clear();
        M.patches[c].overlaps(pose.to_component(M.p), reach_R, kGatherMargin * R_, *comp.collider, *comp.mesh, overlaps_);
        for (const SurfaceOverlap& o : overlaps_) {
            Path k;
            k.a = m;
            k.shot = M.shot;
            k.component = static_cast<int>(c);
            k.path.overlap_m = o.depth_m - kNearMargin * R_;
            k.path.normal = pose.rotation * o.normal;
            k.point_m = pose.to_world(o.point_m);
            k.distance_m = R_ - k.path.overlap_m;
            const double approach = -k.path.normal.dot(M.v - surface_velocity(c, k.point_m));
            k.pair = comp.law->soft()->contact(std::max(0.0, approach));
            paths_.push_back(k);
        }
    }
    for (std::size_t j = 0; j < members_.size(); ++j) {
        if (static_cast<int>(j) == m) continue;
        const Member& B = members_[j];
        const Vec3 d = M.p - B.p;
        const double dist = d.norm();
        if (!(dist < 2.0 * R_ + kNearMargin * R_) || !(dist > 0.0)) continue;
        Path k;
        // The lower index is the contact's shot (the path's normal points towards it).
        const bool first_is_m = M.shot < B.shot;
        k.a = first_is_m ? m : static_cast<int>(j);
        k.b = first_is_m ? static_cast<int>(j) : m;
        k.shot = members_[static_cast<std::size_t>(k.a)].shot;
        k.partner = members_[static_cast<std::size_t>(k.b)].shot;
        k.path.overlap_m = 2.0 * R_ - dist;
        k.path.normal = (first_is_m ? d : Vec3(-d)) / dist;
        k.distance_m = dist;
        const double approach = -k.path.normal.dot(members_[static_cast<std::size_t>(k.a)].v - members_[static_cast<std::size_t>(k.b)].v);
        k.pair = model.shot_shot_law->soft()->contact(std::max(0.0, approach));
        paths_.push_back(k);
    }
    // It flew freely until now: its paths start at the node (no half step behind), and their
    // force there is nil (it joins at its touch).
    node_paths_.resize(paths_.size());
    for (std::size_t k = first; k < paths_.size(); ++k) {
        Path& path = paths_[k];
        shape(path, true);
        shape(path, false);
        node_paths_[k] = node_path(path.pair, path.path, 0.0, dt_);
    }
}

void SoftPool::settle_step(Live& l, double rate, double t) const {
    l.energy_j = 0.5 * l.pair.m_star_kg * rate * rate + contact::soft_elastic_energy(l.pair, l.delta_m);
    if (!(l.start_step_s > 0.0)) {
        l.start_energy_j = std::max(l.energy_j, 0.5 * l.pair.m_star_kg * l.c.approach_m_per_s * l.c.approach_m_per_s);
        l.start_step_s = step_for_contact(l.pair, l.start_energy_j);
    }
    // A contact left to itself only loses energy, and keeps the step of its start; one that a
    // surface loads beyond it (the plate pressing a shot) asks for the shorter step of its energy.
    l.step_s = l.energy_j > l.start_energy_j ? step_for_contact(l.pair, l.energy_j) : l.start_step_s;
    const double age = t - (l.c.start_time_s - epoch_.hi - epoch_.lo);
    l.lively = l.energy_j >= 0.5 * l.pair.m_star_kg * line_speed_ * line_speed_ || age < kSlowAge;
}

int SoftPool::continue_or_begin(int before, const SoftContact& key, double t, double spring_dt, double approach_now, double& spring_step) {
    if (before >= 0) {
        continued_[static_cast<std::size_t>(before)] = 1;
        next_live_.push_back(live_[static_cast<std::size_t>(before)]);
        spring_step = spring_dt;
        return static_cast<int>(next_live_.size()) - 1;
    }
    Live l;
    l.c = key;
    l.c.approach_m_per_s = approach_now;
    l.c.law_state = {};
    const contact::SoftLaw* law =
        key.partner >= 0 ? model_->shot_shot_law->soft() : model_->components[static_cast<std::size_t>(key.component)].law->soft();
    l.pair = law->contact(approach_now);
    next_live_.push_back(l);
    spring_step = t - (key.start_time_s - epoch_.hi - epoch_.lo);  // the part of the step it has lasted
    spring_step = std::clamp(spring_step, 0.0, spring_dt);
    return static_cast<int>(next_live_.size()) - 1;
}

void SoftPool::wall_contacts(int m, double t, double spring_dt, SimulationState& state) {
    const Model& model = *model_;
    Member& M = members_[static_cast<std::size_t>(m)];
    for (std::size_t c = 0; c < model.components.size(); ++c) {
        if ((M.p.array() < reach_lo_[c].array()).any() || (M.p.array() > reach_hi_[c].array()).any()) continue;  // nowhere near
        const Component& comp = model.components[c];
        const Pose& pose = poses_[c];
        overlaps_.clear();
        // Everything within the near margin: the overlaps, and the gaps that get a path.
        M.patches[c].overlaps(pose.to_component(M.p), (1.0 + kNearMargin) * R_, kGatherMargin * R_, *comp.collider, *comp.mesh, overlaps_);
        for (const SurfaceOverlap& o : overlaps_) {
            const Vec3 n = pose.rotation * o.normal;
            const Vec3 q = pose.to_world(o.point_m);
            const double delta = o.depth_m - kNearMargin * R_;  // m, the overlap (negative: a gap)
            Path path;
            path.a = m;
            path.shot = M.shot;
            path.component = static_cast<int>(c);
            path.path.overlap_m = delta;
            path.path.normal = n;
            path.point_m = q;
            path.distance_m = R_ - delta;
            const Vec3 vs = surface_velocity(c, q);
            if (!(delta > 0.0)) {
                // Apart: the pair of the contact that just ended here (its damping), else the law's
                // at the approach now.
                int ended = -1;
                double best = SurfacePatch::kSameContactCos;
                for (const int k : M.contacts) {
                    const Live& l = live_[static_cast<std::size_t>(k)];
                    if (l.c.partner >= 0 || l.c.component != static_cast<int>(c) || !(l.c.normal.dot(n) > best)) continue;
                    best = l.c.normal.dot(n);
                    ended = k;
                }
                path.pair = ended >= 0 ? live_[static_cast<std::size_t>(ended)].pair
                                       : comp.law->soft()->contact(std::max(0.0, -n.dot(M.v_rate - vs)));
                paths_.push_back(path);
                continue;
            }
            const Vec3 r = q - M.p;                         // centre to contact point
            const Vec3 slip_rel = M.v + M.w.cross(r) - vs;  // mid-step: the springs' slip
            const Vec3 slip = slip_rel - slip_rel.dot(n) * n;
            const Vec3 v_rel = M.v_rate + M.w_rate.cross(r) - vs;
            const double vn = v_rel.dot(n);
            const double rate = -vn;  // > 0 while the overlap grows
            const Vec3 vt = v_rel - vn * n;
            // The contact in progress with this component along the nearest normal, if any.
            int before = -1;
            double best = SurfacePatch::kSameContactCos;
            for (const int k : M.contacts) {
                const Live& l = live_[static_cast<std::size_t>(k)];
                if (continued_[static_cast<std::size_t>(k)] || l.c.partner >= 0 || l.c.component != static_cast<int>(c)) continue;
                const double cosine = l.c.normal.dot(n);
                if (cosine > best) best = cosine, before = k;
            }
            SoftContact key;
            double approach = 0.0;
            if (before < 0) {
                key.shot = M.shot;
                key.component = static_cast<int>(c);
                key.mesh_triangle = o.mesh_triangle;
                // It began within this step, when the gap closed (linear in the step).
                const double gap_before = (M.p_before - q).dot(n) - R_;
                const double t_step = t - spring_dt;
                const double began = gap_before > 0.0 ? t_step + spring_dt * gap_before / (gap_before + delta) : t_step;
                key.start_time_s = epoch_.hi + (epoch_.lo + began);
                approach = onset_speed(comp.law->soft()->contact(0.0), gap_before, -(M.v_before - vs).dot(n), rate, delta);
                key.start_point_m = o.point_m;
                key.start_velocity_m_per_s = pose.rotation.transpose() * (M.v - vs);
                const Vec3 rel = M.v - vs;
                key.start_tangential_m_per_s = (rel - rel.dot(n) * n).norm();
            }
            double spring_step = 0.0;
            const int idx = continue_or_begin(before, key, t, spring_dt, approach, spring_step);
            Live& l = next_live_[static_cast<std::size_t>(idx)];
            l.a = m;
            l.b = -1;
            // Its normal force here caps the tangential one (the normal kicks take it along its path).
            const double fn = contact::soft_normal_force(l.pair, delta, rate);
            contact::soft_turn_state(l.pair, l.c.law_state, n);
            const Vec3 ft = contact::soft_tangential_force(l.pair, delta, fn, vt, Vec3(slip * spring_step), l.c.law_state);
            l.c.normal = n;
            l.delta_m = delta;
            l.point_m = q;
            M.f_kick += ft;
            M.tau += r.cross(ft);
            path.live = idx;
            path.pair = l.pair;
            paths_.push_back(path);
            if (delta > contact::kDeepPenetration * R_ && !l.deep) {
                l.deep = true;
                ++state.health.deep_penetrations;
            }
        }
    }
}

void SoftPool::shot_contacts(double t, double spring_dt) {
    // A few members: every pair; more: sorted by x and swept, a pair within 2 R (and the near
    // margin) along x tested.
    const std::size_t n = members_.size();
    if (n < 2) return;
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0);
    const bool sweep = n > kAllPairsUpTo;
    if (sweep)
        std::sort(order_.begin(), order_.end(), [&](int a, int b) {
            const double xa = members_[static_cast<std::size_t>(a)].p.x(), xb = members_[static_cast<std::size_t>(b)].p.x();
            return xa < xb || (xa == xb && members_[static_cast<std::size_t>(a)].shot < members_[static_cast<std::size_t>(b)].shot);
        });
    const double touch = 2.0 * R_, reach = touch + kNearMargin * R_;
    for (std::size_t u = 0; u < n; ++u) {
        for (std::size_t w = u + 1; w < n; ++w) {
            int ma = order_[u], mb = order_[w];
            const double dx = members_[static_cast<std::size_t>(mb)].p.x() - members_[static_cast<std::size_t>(ma)].p.x();
            if (sweep && dx >= reach) break;
            if (!(std::abs(dx) < reach)) continue;
            if (members_[static_cast<std::size_t>(ma)].shot > members_[static_cast<std::size_t>(mb)].shot) std::swap(ma, mb);
            Member& A = members_[static_cast<std::size_t>(ma)];
            Member& B = members_[static_cast<std::size_t>(mb)];
            const Vec3 d = B.p - A.p;
            const double dist = d.norm();
            if (!(dist < reach) || !(dist > 0.0)) continue;
            const Vec3 n = d / dist;            // from A towards B
            const double delta = touch - dist;  // m, the overlap (negative: a gap)
            Path path;
            path.a = ma;
            path.b = mb;
            path.shot = A.shot;
            path.partner = B.shot;
            path.path.overlap_m = delta;
            path.path.normal = -n;  // from the partner towards the shot
            path.distance_m = dist;
            if (!(delta > 0.0)) {
                // Apart: the pair of the contact that just ended here (its damping), else the law's
                // at the approach now.
                int ended = -1;
                for (const int k : A.contacts)
                    if (live_[static_cast<std::size_t>(k)].c.partner == B.shot) ended = k;
                path.pair = ended >= 0 ? live_[static_cast<std::size_t>(ended)].pair
                                       : model_->shot_shot_law->soft()->contact(std::max(0.0, (A.v_rate - B.v_rate).dot(n)));
                paths_.push_back(path);
                continue;
            }
            const double arm = R_ - 0.5 * delta;
            const Vec3 slip_rel = (A.v + A.w.cross(arm * n)) - (B.v + B.w.cross(-arm * n));  // mid-step, A's contact point against B's
            const Vec3 slip = slip_rel - slip_rel.dot(n) * n;
            const Vec3 v_rel = (A.v_rate + A.w_rate.cross(arm * n)) - (B.v_rate + B.w_rate.cross(-arm * n));
            const double rate = v_rel.dot(n);  // > 0 while the overlap grows
            const Vec3 vt = v_rel - rate * n;
            int before = -1;
            for (const int k : A.contacts) {
                const Live& l = live_[static_cast<std::size_t>(k)];
                if (!continued_[static_cast<std::size_t>(k)] && l.c.partner == B.shot) before = k;
            }
            SoftContact key;
            double approach = 0.0;
            if (before < 0) {
                key.shot = A.shot;
                key.partner = B.shot;
                const double gap_before = (B.p_before - A.p_before).norm() - touch;
                const double t_step = t - spring_dt;
                const double began = gap_before > 0.0 ? t_step + spring_dt * gap_before / (gap_before + delta) : t_step;
                key.start_time_s = epoch_.hi + (epoch_.lo + began);
                approach =
                    onset_speed(model_->shot_shot_law->soft()->contact(0.0), gap_before, (A.v_before - B.v_before).dot(n), rate, delta);
            }
            double spring_step = 0.0;
            const int idx = continue_or_begin(before, key, t, spring_dt, approach, spring_step);
            Live& l = next_live_[static_cast<std::size_t>(idx)];
            l.a = ma;
            l.b = mb;
            // Its normal force here caps the tangential one (the normal kicks take it along its path).
            const double fn = contact::soft_normal_force(l.pair, delta, rate);
            contact::soft_turn_state(l.pair, l.c.law_state, n);
            const Vec3 ft = contact::soft_tangential_force(l.pair, delta, fn, vt, Vec3(slip * spring_step), l.c.law_state);  // on A
            l.c.normal = -n;  // from the partner towards the shot
            l.delta_m = delta;
            l.point_m = A.p + arm * n;
            A.f_kick += ft;
            B.f_kick -= ft;
            A.tau += (arm * n).cross(ft);
            B.tau += (-arm * n).cross(-ft);
            path.live = idx;
            path.pair = l.pair;
            paths_.push_back(path);
        }
    }
}

void SoftPool::end_contact(const Live& l, double t, SimulationState& state, std::vector<ImpactRecord>& impacts) {
    const bool impact = contact::is_impact(l.c.approach_m_per_s, line_speed_);
    if (l.c.partner >= 0) {
        if (impact)
            ++state.shot_shot_impacts;
        else if (l.c.approach_m_per_s > 0.0)
            ++state.shot_shot_slow_contacts;
        return;
    }
    const auto c = static_cast<std::size_t>(l.c.component);
    if (!impact) {
        if (l.c.approach_m_per_s > 0.0) ++state.slow_contacts_per_component[c];
        return;
    }
    ++state.impacts_per_component[c];
    const Component& comp = model_->components[c];
    if (!comp.logged || l.a < 0) return;
    const Member& M = members_[static_cast<std::size_t>(l.a)];
    // It separated within the last step, when the gap opened again (linear in the step).
    const double gap = (M.p - l.point_m).dot(l.c.normal) - R_;
    const double ended = gap > 0.0 && last_dt_ > 0.0 ? t - last_dt_ * gap / (gap + l.delta_m) : t;
    const Vec3 vs = comp.kinematics.point_velocity(l.point_m, epoch_, t);
    const Vec3 rel = M.v - vs;
    ImpactRecord rec;
    rec.time_s = l.c.start_time_s;
    rec.shot = M.shot;
    rec.component = l.c.component;
    rec.triangle = walls_.source_facet(c, l.c.mesh_triangle);
    rec.point_m = l.c.start_point_m;
    rec.v_in_m_per_s = l.c.start_velocity_m_per_s;
    rec.vn_in_m_per_s = l.c.approach_m_per_s;
    rec.vt_in_m_per_s = l.c.start_tangential_m_per_s;
    rec.v_out_m_per_s = poses_[c].rotation.transpose() * rel;
    rec.vn_out_m_per_s = std::max(0.0, rel.dot(l.c.normal));
    rec.duration_s = epoch_.hi + (epoch_.lo + ended) - l.c.start_time_s;
    rec.shot_diameter_m = 2.0 * R_;  // one size (the soft scheme refuses a mix)
    impacts.push_back(rec);
}

// ---------------------------------------------------------------------------------------------
// Leaving

void SoftPool::leave(SimulationState& state, std::vector<ImpactRecord>& impacts, std::vector<SoftExit>& exits, StepStats& stats) {
    // Groups of members joined by contacts; a group leaves for rigid sustained contact when none of
    // its contacts is lively.
    const std::size_t n = members_.size();
    // Usually nobody leaves: every member in contact (or just out of one), every contact lively.
    bool quiet = true;
    for (const Member& M : members_)
        quiet = quiet && (M.touching || M.was_touching) && std::isfinite(M.p.squaredNorm() + M.v.squaredNorm());
    for (const Live& l : live_) quiet = quiet && l.lively;
    if (quiet) {
        for (Member& M : members_) M.was_touching = M.touching;
        return;
    }
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), 0);
    const auto root = [&](int x) {
        while (parent_[static_cast<std::size_t>(x)] != x)
            x = parent_[static_cast<std::size_t>(x)] = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(x)])];
        return x;
    };
    bool any_slow = false;
    for (const Live& l : live_) {
        any_slow |= !l.lively;
        if (l.b >= 0) parent_[static_cast<std::size_t>(root(l.a))] = root(l.b);
    }
    lively_.assign(n, 0);
    if (any_slow) {
        for (const Live& l : live_)
            if (l.lively) lively_[static_cast<std::size_t>(root(l.a))] = 1;
    }
    leaving_.assign(n, 0);
    for (std::size_t m = 0; m < n; ++m) {
        const Member& M = members_[m];
        if (!std::isfinite(M.p.squaredNorm() + M.v.squaredNorm() + M.w.squaredNorm())) {
            leaving_[m] = 3;  // lost
            continue;
        }
        if (!M.touching && !M.was_touching)
            leaving_[m] = 1;  // a whole step without contact: flies
        else if (any_slow && M.touching && !lively_[static_cast<std::size_t>(root(static_cast<int>(m)))])
            leaving_[m] = 2;  // rests
    }
    for (std::size_t m = 0; m < n; ++m) members_[m].was_touching = members_[m].touching;
    if (std::find_if(leaving_.begin(), leaving_.end(), [](unsigned char x) { return x != 0; }) == leaving_.end()) return;

    // The contacts of the members that leave end with them (a group leaves whole, so none joins a
    // member that stays); what remains keeps its order.
    next_live_.clear();
    for (const Live& l : live_) {
        if (leaving_[static_cast<std::size_t>(l.a)] != 0 || (l.b >= 0 && leaving_[static_cast<std::size_t>(l.b)] != 0)) continue;
        next_live_.push_back(l);
    }
    for (std::size_t m = 0; m < n; ++m) {
        if (!leaving_[m]) continue;
        const Member& M = members_[m];
        SoftExit e;
        e.shot = M.shot;
        e.position_m = M.p;
        e.velocity_m_per_s = M.v;
        if (leaving_[m] == 3) {
            e.to = SoftExit::To::lost;
        } else if (leaving_[m] == 2) {
            // Rigid sustained contact from here: out of each surface it overlaps, its approach to
            // each taken away, resting on the normal gravity presses on most.
            e.to = SoftExit::To::rest;
            for (const Live& l : live_) {
                if (l.a != static_cast<int>(m) && l.b != static_cast<int>(m)) continue;
                const Vec3 n = l.b == static_cast<int>(m) ? Vec3(-l.c.normal) : l.c.normal;  // towards this shot
                if (l.c.partner < 0) {
                    e.position_m += l.delta_m * n;
                    const Vec3 vs =
                        model_->components[static_cast<std::size_t>(l.c.component)].kinematics.point_velocity(l.point_m, epoch_, t_);
                    const double vn = (e.velocity_m_per_s - vs).dot(n);
                    if (vn < 0.0) e.velocity_m_per_s -= vn * n;
                }
                if (g_.dot(n) < g_.dot(e.support)) e.support = n;
            }
            ++stats.soft_rests;
        }
        state.shots.set_spin(static_cast<std::size_t>(M.shot), e.to == SoftExit::To::lost ? Vec3(Vec3::Zero()) : M.w);
        exits.push_back(e);
    }
    // Their contacts end: counted (and logged) as they stand.
    for (const Live& l : live_) {
        if (leaving_[static_cast<std::size_t>(l.a)] == 0 && (l.b < 0 || leaving_[static_cast<std::size_t>(l.b)] == 0)) continue;
        end_contact(l, t_, state, impacts);
    }
    std::swap(live_, next_live_);
    // Their paths go with them, a pair's both ways: a member that stays feels nothing more from
    // one that left (the scheme around finds their touch, if any, exactly).
    std::size_t kept = 0;
    for (std::size_t i = 0; i < paths_.size(); ++i) {
        const Path& k = paths_[i];
        if (leaving_[static_cast<std::size_t>(k.a)] != 0 || (k.b >= 0 && leaving_[static_cast<std::size_t>(k.b)] != 0)) continue;
        if (kept != i) {
            paths_[kept] = paths_[i];
            node_paths_[kept] = node_paths_[i];
        }
        ++kept;
    }
    paths_.resize(kept);
    node_paths_.resize(kept);
    for (std::size_t m = n; m-- > 0;)
        if (leaving_[m]) remove_member(static_cast<int>(m));
    for (Live& l : live_) {
        l.a = member_of_[static_cast<std::size_t>(l.c.shot)];
        l.b = l.c.partner >= 0 ? member_of_[static_cast<std::size_t>(l.c.partner)] : -1;
    }
    for (Path& k : paths_) {
        k.a = member_of_[static_cast<std::size_t>(k.shot)];
        k.b = k.partner >= 0 ? member_of_[static_cast<std::size_t>(k.partner)] : -1;
    }
    if (members_.empty()) pending_step_ = 0.0;
}

// ---------------------------------------------------------------------------------------------
// Restart points

void SoftPool::save(SimulationState& state) const {
    state.soft_contacts.clear();
    for (const Live& l : live_) state.soft_contacts.push_back(l.c);
    std::sort(state.soft_contacts.begin(), state.soft_contacts.end(), [](const SoftContact& a, const SoftContact& b) {
        return std::tie(a.shot, a.partner, a.component, a.mesh_triangle) < std::tie(b.shot, b.partner, b.component, b.mesh_triangle);
    });
    for (const Member& M : members_) state.shots.set_spin(static_cast<std::size_t>(M.shot), M.w);
}

const std::vector<int>& SoftPool::restore(SoftSurroundings& around, SimulationState& state, std::vector<ImpactRecord>& impacts,
                                          std::vector<SoftExit>& exits, StepStats& stats) {
    restored_.clear();
    live_.clear();
    for (const SoftContact& c : state.soft_contacts) {
        for (const int shot : {c.shot, c.partner}) {
            if (shot < 0 || contains(shot)) continue;
            const auto k = static_cast<std::size_t>(shot);
            add_member(shot, state.shots.position(k), state.shots.velocity(k), state.shots.spin(k));
            restored_.push_back(shot);
        }
        Live l;
        l.c = c;
        const contact::SoftLaw* law =
            c.partner >= 0 ? model_->shot_shot_law->soft() : model_->components[static_cast<std::size_t>(c.component)].law->soft();
        l.pair = law->contact(c.approach_m_per_s);
        live_.push_back(l);
    }
    state.soft_contacts.clear();
    if (members_.empty()) return restored_;
    for (const int shot : restored_) around.joined(shot, t_);
    // Their forces now (the springs as saved), so that the first step starts as the one it continues.
    evaluate(t_, 0.0, state, impacts, stats);
    for (Member& M : members_) M.was_touching = true;
    for (std::size_t m = 0; m < members_.size(); ++m) renew_box(static_cast<int>(m), around);
    leave(state, impacts, exits, stats);
    report(around);
    return restored_;
}

}  // namespace peensim
