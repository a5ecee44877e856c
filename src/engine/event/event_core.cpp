#include "engine/event/event_core.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/float_limits.h"
#include "engine/law_input.h"
#include "engine/time_stepping.h"

namespace peensim {

namespace {

constexpr double kSubstep = 50e-6;                    // s, sustained-contact substep (fall per substep g t^2/2 = 12 nm)
constexpr double kSubstepTravel = 0.25;               // of R, the most a shot (or a turning surface) moves in a substep
constexpr double kMinImpactSpeed = 1e-6;              // m/s, slower approaches are never impacts
constexpr double kBoxTravel = 4.0;                    // radii of travel a flight's first search window (and box) covers
constexpr double kMinBoxHorizon = 1e-7;               // s, a box horizon moves time on at least this much
constexpr std::uint64_t kMaxEventsAtOneTime = 10000;  // then the shot is forced into substeps

// Slower approaches than gravity adds over two substeps are sustained contact (time stepping's rule).
// Never zero: a touch at a rounding-level speed (a flight exactly tangent to a face, without
// gravity) is not an impact either.
double resting_speed_for(const Model& m) { return std::max(kMinImpactSpeed, 2.0 * m.gravity_m_per_s2.norm() * kSubstep); }

}  // namespace

EventCore::EventCore(std::shared_ptr<const Model> model)
    : model_(model),
      pairs_(model->shot_count, resting_speed_for(*model)),
      walls_(model),
      sustained_(std::move(model), resting_speed_for(*model_)),
      contact_state_(uses_contact_state(*model_)) {
    const Model& m = *model_;
    // Every kernel here solves exact parabolas; a scene with another flight runs time stepping.
    if (!m.flight->is_parabola())
        throw std::logic_error("the event-driven schemes need parabolic flights; this model's are '" + std::string(m.flight->name()) + "'");
    R_ = m.min_shot_radius_m;
    R_max_ = m.max_shot_radius_m;
    g_ = m.gravity_m_per_s2;
    substep_ = kSubstep;
    resting_speed_ = resting_speed_for(m);
    impact_speed_ = m.impact_speed_m_per_s;
    box_travel_ = kBoxTravel * R_;
    shots_.resize(static_cast<std::size_t>(m.shot_count));
    active_.assign(shots_.size(), 0);
    queue_.reset(shots_.size());
    neighbours_.reserve(64);
    wake_stack_.reserve(64);
    woken_.reserve(64);
}

// ---------------------------------------------------------------------------------------------
// Intervals between restart points

void EventCore::open_interval(double now_s) {
    started_ = true;
    next_restart_ = next_multiple(now_s, kRestartInterval);
    work_since_restart_ = 0;
}

void EventCore::start_from(SimulationState& state) {
    // The budget follows from the restart's own work, which depends on the state alone: a resumed
    // run restarts where the uninterrupted one does.
    const std::uint64_t before = work_units();
    start(state);
    work_counted_ = work_units();
    work_budget_ = std::max(kMinWorkBudget, kWorkPerRestart * (work_counted_ - before));
}

// ---------------------------------------------------------------------------------------------
// The event loop

EventCore::Stop EventCore::advance(SimulationState& state, double t_end_s, double pause_at_s, std::vector<ImpactRecord>& impacts) {
    const double now_s = state.time.seconds();
    // Where this call stops (absolute s): the end, the caller's pause, the next point of the sync grid
    // or the next restart point. Only the grid and restart points may change the dynamics (a restart),
    // and they do not depend on where the caller pauses.
    const double grid_s = next_multiple(now_s, kSyncInterval);
    double stop_s = std::min({t_end_s, pause_at_s, grid_s, next_restart_});
    const double now = since_epoch(now_s);
    double t_stop = std::max(now, since_epoch(stop_s));
    for (;;) {
        // The pool's next step takes its turn in time order with the events (first on a tie).
        if (pool_ && pool_->next_step_end() <= queue_.top_time()) {
            if (pool_->next_step_end() > t_stop) break;
            const double pool_time = pool_->step(state, impacts);
            const std::uint64_t done = work_units();
            const bool due = count_work(done - work_counted_, absolute_seconds(pool_time));
            work_counted_ = done;
            if (due && next_restart_ < stop_s) {
                stop_s = next_restart_;
                t_stop = std::max(now, since_epoch(stop_s));
            }
            continue;
        }
        if (!(queue_.top_time() <= t_stop)) break;
        const int i = queue_.top();
        const double t = queue_.top_time();
        // Forced progress (pitfall 5): should a shot keep producing events without time moving on,
        // it is advanced in substeps, which always move time forward.
        at_same_time_ = t == same_time_ ? at_same_time_ + 1 : 0;
        same_time_ = t;
        if (at_same_time_ > kMaxEventsAtOneTime) {
            // Contacts at this instant are left to the substeps of sustained contact.
            ++state.health.unresolved_contacts;
            shots_[static_cast<std::size_t>(i)].no_pairs_at = t;
            set_flight(i, position(i, t), velocity(i, t), t, Motion::sustained);
            predict(i, t);
            at_same_time_ = 0;
            continue;
        }
        ++stats_.events;
        ++events_since_sync_;
        process(i, state, impacts);
        const std::uint64_t done = work_units();
        const bool due = count_work(done - work_counted_, absolute_seconds(t));
        work_counted_ = done;
        if (due && next_restart_ < stop_s) {
            stop_s = next_restart_;
            t_stop = std::max(now, since_epoch(stop_s));
        }
    }

    // A restart point comes next: the pool steps exactly there, and its contacts go into the state.
    if (pool_ && stop_s >= next_restart_) pool_->finish_interval(t_stop, state, impacts);
    // Bring the state up to t_stop: exact positions on every shot's current flight.
    StageTimer timer(stats_, Stage::integrate);
    ShotArrays& s = state.shots;
    double fastest2 = 0.0;
    for (std::size_t k = 0; k < shots_.size(); ++k) {
        if (!active_[k]) continue;
        const int i = static_cast<int>(k);
        s.set_position(k, position(i, t_stop));
        const Vec3 v = velocity(i, t_stop);
        s.set_velocity(k, v);
        if (pool_ && pool_->contains(i)) s.set_spin(k, pool_->spin(i));
        s.in_flight[k] = shots_[k].in_flight;
        fastest2 = std::max(fastest2, v.squaredNorm());
    }
    state.fastest_shot_m_per_s = std::sqrt(fastest2);
    // The stop is one of the absolute times above, so the state's time is that exact double: the
    // scheme's own times are relative to its epoch, never the other way round.
    if (stop_s > now_s) state.time = SimTime{stop_s, 0.0};
    ++state.steps;
    state.shot_steps += events_since_sync_;
    events_since_sync_ = 0;
    state.health.unresolved_contacts += unresolved_;
    unresolved_ = 0;
    state.health.search_fallbacks += search_fallbacks_;
    search_fallbacks_ = 0;
    if (state.first_search_fallback.time_s < 0.0 && first_fallback_.time_s >= 0.0) state.first_search_fallback = first_fallback_;
    first_fallback_ = SearchFallback{};
    if (stop_s >= next_restart_) started_ = false;  // the next advance() starts afresh from this state
    return Stop{stop_s, grid_s};
}

void EventCore::fit_shots(std::size_t n) {
    if (n <= shots_.size()) return;
    shots_.resize(n);
    active_.resize(n, 0);
    queue_.grow(n);
    pairs_.grow(static_cast<int>(n));
    if (pool_) pool_->grow(n);
}

void EventCore::take_new_shots(SimulationState& state, const std::vector<int>& shots) {
    // The scheme stopped at the emission time (Simulation pauses there): the shot fly from now.
    const double t = since_epoch(state.time.seconds());
    for (const int i : shots) {
        const auto k = static_cast<std::size_t>(i);
        // A reused slot keeps counting its versions: a pair event predicted against the shot that
        // was there must stay stale.
        const std::uint32_t version = shots_[k].version;
        shots_[k] = Shot{};
        shots_[k].version = version;
        shots_[k].radius_m = shot_radius(*model_, state.shots, k);
        active_[k] = 1;
        set_flight(i, state.shots.position(k), state.shots.velocity(k), t, Motion::flying);
        shots_[k].in_flight = true;
        predict_wall(i, t);
        renew_box(i, t);
        shots_[k].pair_time = kInf;
        schedule(i);
    }
    for (const int i : shots) pairs_and_schedule(i, t);
}

bool EventCore::count_work(std::uint64_t units, double now_s) {
    const bool was_due = work_since_restart_ >= work_budget_;
    work_since_restart_ += units;
    if (was_due || work_since_restart_ < work_budget_) return false;
    // Enough work since the last restart point: the next point of the sync grid is one, so that
    // checkpoints and interrupts come often in wall time too. Counted in events (or time-stepped
    // shot steps), never in wall time, so that an uninterrupted run restarts where a resumed one does.
    next_restart_ = std::min(next_restart_, next_multiple(now_s, kSyncInterval));
    return true;
}

double EventCore::next_multiple(double t_s, double step_s) {
    double k = std::floor(t_s / step_s);
    while (k * step_s <= t_s) k += 1.0;
    return k * step_s;
}

double EventCore::since_epoch(double t_s) const { return (t_s - epoch_.hi) - epoch_.lo; }

double EventCore::absolute_seconds(double t) const { return epoch_.hi + (epoch_.lo + t); }

void EventCore::start(SimulationState& state) {
    if (state.shots.in_flight.size() != state.shots.size()) state.shots.in_flight.assign(state.shots.size(), 0);
    if (state.slow_contacts_per_component.size() != model_->components.size())
        state.slow_contacts_per_component.resize(model_->components.size(), 0);
    // The scheme's clock starts here: every time it keeps is seconds since this epoch, so a contact
    // time is resolved to ~1e-17 s however long the run (an absolute double at 2048 s resolves only
    // 4.5e-13 s, which at a few m/s is a position error above the touch tolerances).
    epoch_ = state.time;
    walls_.set_epoch(epoch_);
    same_time_ = -1.0;
    at_same_time_ = 0;
    const double t = 0.0;
    // Everything from the state alone, as after a resume: fresh tree, queue and per-shot records.
    fit_shots(state.shots.size());
    pairs_.reset();
    queue_.reset(shots_.size());
    std::fill(shots_.begin(), shots_.end(), Shot{});
    // Two passes: every flight and its box first, so that the pair predictions see every neighbour.
    for (std::size_t k = 0; k < shots_.size(); ++k) {
        active_[k] = state.shots.active[k];
        if (!active_[k]) continue;
        const int i = static_cast<int>(k);
        shots_[k].radius_m = shot_radius(*model_, state.shots, k);
        // A shot exactly still and touching a surface was asleep (sleeping shot are synchronised
        // with a zero velocity): it sleeps on, as it would in a run resumed from this state.
        const Vec3 p = state.shots.position(k), v = state.shots.velocity(k);
        const bool asleep = v == Vec3::Zero() && touches_surface(p, shots_[k].radius_m);
        // A shot whose contacts a law remembers is in sustained contact: it goes on in substeps (a
        // flight would end those contacts, and their state, at every restart point).
        const bool sustained = !asleep && contact_state_ && has_contacts(state.contacts, i);
        set_flight(i, p, v, t, asleep ? Motion::sleeping : sustained ? Motion::sustained : Motion::flying);
        shots_[k].in_flight = state.shots.in_flight[k] != 0;
        predict_wall(i, t);
        renew_box(i, t);
        shots_[k].pair_time = kInf;
        schedule(i);
    }
    // The pool's contacts in progress go on: their shot are the pool's again.
    if (pool_) pool_->restore(epoch_, state);
    for (std::size_t k = 0; k < shots_.size(); ++k) {
        if (!active_[k] || (pool_ && pool_->contains(static_cast<int>(k)))) continue;
        pairs_and_schedule(static_cast<int>(k), t);
    }
    if (pool_) pool_->settle(state);
}

double EventCore::resting_fraction(const SimulationState& state, double share_that_matters, double still_speed_m_per_s) const {
    // Still shot (slower than still_speed_m_per_s) touching a surface or another still shot, over the
    // active ones. Neighbours by a sweep along x over the still shot sorted by x.
    const double reach = 2.0 * R_max_ * (1.0 + kContactSlack);  // the sweep's window; each pair is checked at its own
    std::size_t active = 0;
    std::vector<std::pair<double, std::size_t>> still;
    for (std::size_t k = 0; k < state.shots.size(); ++k) {
        if (!state.shots.active[k]) continue;
        ++active;
        if (state.shots.velocity(k).norm() < still_speed_m_per_s) still.emplace_back(state.shots.x[k], k);
    }
    if (active == 0 || static_cast<double>(still.size()) <= share_that_matters * static_cast<double>(active)) return 0.0;
    std::sort(still.begin(), still.end());
    std::vector<unsigned char> resting(still.size(), 0);
    for (std::size_t a = 0; a < still.size(); ++a) {
        const std::size_t ka = still[a].second;
        const double Ra = shot_radius(*model_, state.shots, ka);
        if (!resting[a] && touches_surface(state.shots.position(ka), Ra)) resting[a] = 1;
        for (std::size_t b = a + 1; b < still.size() && still[b].first - still[a].first < reach; ++b) {
            const std::size_t kb = still[b].second;
            const double touch = (Ra + shot_radius(*model_, state.shots, kb)) * (1.0 + kContactSlack);
            if ((state.shots.position(ka) - state.shots.position(kb)).norm() < touch) resting[a] = resting[b] = 1;
        }
    }
    return static_cast<double>(std::count(resting.begin(), resting.end(), 1)) / static_cast<double>(active);
}

bool EventCore::touches_surface(const Vec3& p, double R) const {
    for (const Component& comp : model_->components) {
        if (comp.kinematics.moves()) continue;  // nothing rests on a vibrating plate or a turning part
        MeshCollider::Closest closest;
        MeshCollider::QueryCounters counters;
        if (comp.collider->closest_within(comp.kinematics.rest.to_component(p), R * (1.0 + kContactSlack), closest, counters)) return true;
    }
    return false;
}

double EventCore::key(const Shot& s) const { return std::min({s.wall.time, s.pair_time, s.box_until}); }

void EventCore::schedule(int i) { queue_.set(i, key(shots_[static_cast<std::size_t>(i)])); }

void EventCore::process(int i, SimulationState& state, std::vector<ImpactRecord>& impacts) {
    Shot& s = shots_[static_cast<std::size_t>(i)];
    const double t = queue_.top_time();
    if (s.pair_time <= s.wall.time && s.pair_time <= s.box_until) {
        const int j = s.partner;
        if (!active_[static_cast<std::size_t>(j)] || shots_[static_cast<std::size_t>(j)].version != s.partner_version) {
            // Lazy invalidation: the partner's flight changed since this was predicted.
            ++stats_.stale_events;
            pairs_and_schedule(i, t);
            return;
        }
        collide_pair(i, j, t, state, impacts);
        return;
    }
    if (s.wall.time <= s.box_until) {
        collide_wall(i, t, state, impacts);
        return;
    }
    ++stats_.box_renewals;
    renew_box(i, t);
    pairs_and_schedule(i, t);
}

// ---------------------------------------------------------------------------------------------
// Flights and predictions

void EventCore::set_flight(int i, const Vec3& p, const Vec3& v, double t, Motion motion, const Vec3& support) {
    start_motion(shots_[static_cast<std::size_t>(i)], p, v, t, motion, g_, box_travel_, support);
}

Vec3 EventCore::position(int i, double t) const {
    if (pool_ && pool_->contains(i)) return pool_->position(i, t);
    return motion_position(shots_[static_cast<std::size_t>(i)], walls_, t);
}

Vec3 EventCore::velocity(int i, double t) const {
    if (pool_ && pool_->contains(i)) return pool_->velocity(i, t);
    return motion_velocity(shots_[static_cast<std::size_t>(i)], walls_, t);
}

void EventCore::predict(int i, double t) {
    predict_wall(i, t);
    renew_box(i, t);
    pairs_and_schedule(i, t);
}

void EventCore::pairs_and_schedule(int i, double t) {
    const bool joins_pile = pairs_.predict(i, t, shots_, active_, queue_, stats_);
    if (pool_) pool_->predicted(i, pairs_.pooled_neighbours());
    if (joins_pile) {
        // Pressed into a pile (shot in sustained contact or asleep): it joins the pile's sustained
        // contact, which resolves it with the others substep by substep.
        set_flight(i, position(i, t), velocity(i, t), t, Motion::sustained);
        predict(i, t);
        return;
    }
    schedule(i);
}

void EventCore::predict_wall(int i, double t) {
    Shot& s = shots_[static_cast<std::size_t>(i)];
    WallEvent& w = s.wall;
    w = WallEvent{};
    switch (s.motion) {
        case Motion::riding: return;  // start_ride set the launch
        case Motion::sustained: {
            // Contacts are looked for at the substep's end only, so a substep may not carry the
            // shot (or a turning part's surface, or the vibrating sonotrode's when the shot is
            // near it) further than a quarter radius: nothing can be crossed unseen, as with time
            // stepping's travel limit.
            const Vec3 p = position(i, t);
            // Every sonotrode the shot is near moves its surface too.
            double near_sonotrode = 0.0;  // m/s
            for (std::size_t c = 0; c < model_->components.size(); ++c) {
                const Component& sono = model_->components[c];
                if (sono.role != ComponentRole::sonotrode) continue;
                const Vec3 reach = Vec3::Constant(2.0 * s.radius_m + sono.kinematics.amplitude_m);
                if (((p.array() > (sono.world_lo - reach).array()) && (p.array() < (sono.world_hi + reach).array())).all())
                    near_sonotrode = std::max(near_sonotrode, walls_.surface_speed(c));
            }
            const double speed = velocity(i, t).norm() + walls_.moving_part_speed() + near_sonotrode;
            s.substep_s = speed > 0.0 ? std::clamp(kSubstepTravel * s.radius_m / speed, kMinBoxHorizon, substep_) : substep_;
            w.time = t + s.substep_s;
            w.kind = WallKind::substep;
            return;
        }
        case Motion::sleeping:
        case Motion::pooled:  // the pool finds its contacts
            w.time = kInf;
            w.kind = WallKind::none;
            return;
        case Motion::flying: break;
    }
    StageTimer timer(stats_, Stage::mesh_queries);
    // Only a window of the flight is searched, a few radii of travel: the next event is usually a
    // neighbour or a surface close by, and a short sweep visits few BVH nodes. If nothing is found,
    // the window's end is an event that searches the next one (and renews the neighbour box).
    // Windows double while nothing is found (a long free flight costs a few searches, not many).
    const double window = std::max(kMinBoxHorizon, TimeStepping::step_for(s.path.velocity(t).norm(), g_.norm(), s.window_travel));
    const Trajectory path = s.path.rebased(t);
    // Right after a graze (a touch with no approach on a surface that does not press the shot), the
    // surfaces are searched from a hair later: the touch itself, read again at the same instant,
    // would be found again (its approach sign is rounding), forever. Within the hair the shot moves
    // 1e-9 R: anything it could enter meanwhile is found overlapping by this search.
    const double t_search = t == s.graze_at ? t + kTouchDistance * s.radius_m / std::max(path.v0.norm(), resting_speed_) : t;
    w = walls_.first_event(path, s.radius_m, t, t_search, t + window, stats_);
    s.resumed_searches = w.resumed ? s.resumed_searches + 1 : 0;
    if (s.resumed_searches < kMaxResumedSearches) return;
    // The search fallback (see the header): the exact search makes no headway; substeps do.
    ++search_fallbacks_;
    if (first_fallback_.time_s < 0.0) first_fallback_ = SearchFallback{absolute_seconds(t), i, w.component, position(i, t)};
    s.resumed_searches = 0;
    set_flight(i, position(i, t), velocity(i, t), t, Motion::sustained);
    predict_wall(i, t);
}

void EventCore::renew_box(int i, double t) {
    Shot& s = shots_[static_cast<std::size_t>(i)];
    const double pad = 1e-9 * R_ + 1e-15;
    Vec3 lo, hi;
    if (s.motion == Motion::sleeping) {
        lo = hi = s.path.p0;
        s.box_until = kInf;
    } else {
        // A flying shot's box covers its searched window; others' a few radii of travel.
        const double horizon = std::max(kMinBoxHorizon, TimeStepping::step_for(velocity(i, t).norm(), g_.norm(), box_travel_));
        s.box_until = s.motion == Motion::flying ? s.wall.time : std::min(s.wall.time, t + horizon);
        if (s.motion == Motion::riding) {
            s.path.bounds(t, s.box_until, lo, hi);
            const Vec3 swing = Vec3::Constant(2.0 * walls_.face(static_cast<std::size_t>(s.ride_component)).plane.amplitude_m);
            lo -= swing, hi += swing;  // riders follow the plate; their path leaves it out
        } else {
            s.path.bounds(t, s.box_until, lo, hi);
        }
    }
    s.box_lo = lo - Vec3::Constant(s.radius_m + pad);
    s.box_hi = hi + Vec3::Constant(s.radius_m + pad);
    pairs_.set_box(i, s.box_lo, s.box_hi);
}

bool EventCore::still_more_than(double share) const {
    std::size_t active = 0, still = 0;
    for (std::size_t k = 0; k < shots_.size(); ++k) {
        if (!active_[k]) continue;
        ++active;
        still += shots_[k].motion == Motion::sustained || shots_[k].motion == Motion::sleeping;
    }
    return static_cast<double>(still) > share * static_cast<double>(active);
}

void EventCore::unschedule(int i) { queue_.set(i, kInf); }

}  // namespace peensim
