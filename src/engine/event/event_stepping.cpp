#include "engine/event/event_stepping.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "collision/surface_clearance.h"
#include "engine/impact_recording.h"
#include "engine/law_input.h"
#include "engine/loss_diagnosis.h"
#include "engine/time_stepping.h"
#include "kernels/plate_release.h"

namespace peensim {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kSubstep = 50e-6;       // s, sustained-contact substep (fall per substep g t^2/2 = 12 nm)
constexpr double kSubstepTravel = 0.25;  // of R, the most a shot (or a turning surface) moves in a substep
// Hand-over to time stepping: at a restart point, when more than this fraction of the shot lie still
// (slower than kHandOverSpeed) on a surface, the next interval is time-stepped.
constexpr double kHandOverFraction = 0.1;
constexpr double kHandOverSpeed = 0.05;               // m/s
constexpr double kMinImpactSpeed = 1e-6;              // m/s, slower approaches are never impacts
constexpr double kBoxTravel = 4.0;                    // radii of travel a flight's first search window (and box) covers
constexpr double kMaxWindowTravel = 64.0;             // radii: windows double up to this while a flight finds nothing
constexpr double kMinBoxHorizon = 1e-7;               // s, a box horizon moves time on at least this much
constexpr double kCollapseWindow = 1e-6;              // s, TC rule: a shot-shot collision this soon after one is elastic
constexpr int kMaxQuickGrazes = 4;                    // grazes each within kCollapseWindow of the last, then sustained contact
constexpr std::uint64_t kMaxEventsAtOneTime = 10000;  // then the shot is forced into substeps

// Slower approaches than gravity adds over two substeps are sustained contact (time stepping's rule).
// Never zero: a touch at a rounding-level speed (a flight exactly tangent to a face, without
// gravity) is not an impact either.
double resting_speed_for(const Model& m) { return std::max(kMinImpactSpeed, 2.0 * m.gravity_m_per_s2.norm() * kSubstep); }

}  // namespace

EventStepping::EventStepping(std::shared_ptr<const Model> model)
    : model_(model),
      pairs_(model->shot_count, resting_speed_for(*model)),
      walls_(model),
      sustained_(std::move(model), resting_speed_for(*model_)),
      contact_state_(uses_contact_state(*model_)) {
    const Model& m = *model_;
    // Every kernel here solves exact parabolas; a scene with another flight runs time stepping.
    if (!m.flight->is_parabola())
        throw std::logic_error("the event scheme needs parabolic flights; this model's are '" + std::string(m.flight->name()) + "'");
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
    if (m.scheme == SteppingScheme::soft) soft_ = std::make_unique<SoftPool>(model_, walls_);
    neighbours_.reserve(64);
    wake_stack_.reserve(64);
    woken_.reserve(64);
}

EventStepping::~EventStepping() = default;

const StepStats& EventStepping::stats() const {
    combined_ = stats_;
    if (hand_over_) combined_ += hand_over_->stats();
    return combined_;
}

// ---------------------------------------------------------------------------------------------
// The event loop

void EventStepping::advance(SimulationState& state, double t_end_s, double pause_at_s, std::vector<ImpactRecord>& impacts) {
    const double now_s = state.time.seconds();
    if (!(t_end_s > now_s)) return;
    if (!started_) {
        started_ = true;
        next_restart_ = next_multiple(now_s, kRestartInterval);
        work_since_restart_ = 0;
        // A load mostly at rest (sonotrode off, a chamber filled with shot) is time stepping's regime:
        // its sustained contacts resolve whole piles at once, where events would crawl through them
        // shot by shot. Decided from the state alone, so a resumed run decides the same.
        // (Never in the soft scheme: time stepping has no soft contacts, and would resolve an impact
        // into the load rigidly; its sustained contacts and sleep keep a load at rest cheap there.)
        handed_over_ = !soft_ && resting_fraction(state) > kHandOverFraction;
        if (handed_over_) {
            if (!hand_over_) hand_over_ = std::make_unique<TimeStepping>(model_);
            ++stats_.hand_overs;
            work_budget_ = std::max(kMinWorkBudget, kWorkPerRestart * kWorkPerShotStep * static_cast<std::uint64_t>(state.shots.size()));
        } else {
            // The budget follows from the restart's own work, which depends on the state alone: a
            // resumed run restarts where the uninterrupted one does.
            const std::uint64_t before = work_units();
            start(state);
            work_counted_ = work_units();
            work_budget_ = std::max(kMinWorkBudget, kWorkPerRestart * (work_counted_ - before));
        }
    }
    if (handed_over_) {
        const std::uint64_t steps_before = state.shot_steps;
        hand_over_->advance(state, std::min(t_end_s, next_restart_), pause_at_s, impacts);
        count_work(kWorkPerShotStep * (state.shot_steps - steps_before), state.time.seconds());
        if (state.time.seconds() >= next_restart_) started_ = false;
        return;
    }
    // Where this call stops (absolute s): the end, the caller's pause, the next point of the sync grid
    // or the next restart point. Only the grid and restart points may change the dynamics (a restart),
    // and they do not depend on where the caller pauses.
    const double grid_s = next_multiple(now_s, kSyncInterval);
    double stop_s = std::min({t_end_s, pause_at_s, grid_s, next_restart_});
    const double now = since_epoch(now_s);
    double t_stop = std::max(now, since_epoch(stop_s));
    for (;;) {
        // The soft pool's next step takes its turn in time order with the events (first on a tie).
        if (soft_ && soft_->next_step_end() <= queue_.top_time()) {
            if (soft_->next_step_end() > t_stop) break;
            soft_->step(*this, state, impacts, exits_, stats_);
            take_exits(state);
            const std::uint64_t done = work_units();
            const bool due = count_work(done - work_counted_, absolute_seconds(soft_->time()));
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
    if (soft_ && stop_s >= next_restart_) {
        soft_->step_to(t_stop, *this, state, impacts, exits_, stats_);
        take_exits(state);
        soft_->save(state);
    }
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
        if (soft_ && soft_->contains(i)) s.set_spin(k, soft_->spin(i));
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
    // Most shot in sustained contact or asleep, and the state says the load is at rest: restart at
    // this grid point, to hand the load over to time stepping (see above). Looked at on the grid only,
    // so that where a caller pauses never changes the run.
    if (!started_ || stop_s != grid_s || soft_) return;
    std::size_t active = 0, still = 0;
    for (std::size_t k = 0; k < shots_.size(); ++k) {
        if (!active_[k]) continue;
        ++active;
        still += shots_[k].motion == Motion::sustained || shots_[k].motion == Motion::sleeping;
    }
    if (static_cast<double>(still) > kHandOverFraction * static_cast<double>(active) && resting_fraction(state) > kHandOverFraction)
        started_ = false;
}

void EventStepping::state_changed() {
    started_ = false;
    if (hand_over_) hand_over_->state_changed();
}

void EventStepping::fit_shots(std::size_t n) {
    if (n <= shots_.size()) return;
    shots_.resize(n);
    active_.resize(n, 0);
    queue_.grow(n);
    pairs_.grow(static_cast<int>(n));
    if (soft_) soft_->grow(n);
}

void EventStepping::shots_added(SimulationState& state, const std::vector<int>& shots) {
    fit_shots(state.shots.size());
    if (hand_over_) hand_over_->shots_added(state, shots);
    // Between restart points (or time-stepped) nothing is kept that a new shot could upset: the
    // next start() takes it from the state with the others.
    if (!started_ || handed_over_) return;
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

bool EventStepping::count_work(std::uint64_t units, double now_s) {
    const bool was_due = work_since_restart_ >= work_budget_;
    work_since_restart_ += units;
    if (was_due || work_since_restart_ < work_budget_) return false;
    // Enough work since the last restart point: the next point of the sync grid is one, so that
    // checkpoints and interrupts come often in wall time too. Counted in events (or time-stepped
    // shot steps), never in wall time, so that an uninterrupted run restarts where a resumed one does.
    next_restart_ = std::min(next_restart_, next_multiple(now_s, kSyncInterval));
    return true;
}

double EventStepping::next_multiple(double t_s, double step_s) {
    double k = std::floor(t_s / step_s);
    while (k * step_s <= t_s) k += 1.0;
    return k * step_s;
}

double EventStepping::since_epoch(double t_s) const { return (t_s - epoch_.hi) - epoch_.lo; }

double EventStepping::absolute_seconds(double t) const { return epoch_.hi + (epoch_.lo + t); }

void EventStepping::start(SimulationState& state) {
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
    // The soft contacts in progress go on: their shot are the pool's again.
    std::vector<ImpactRecord> none;
    if (soft_) {
        soft_->reset(epoch_, shots_.size());
        soft_->restore(*this, state, none, exits_, stats_);
    }
    for (std::size_t k = 0; k < shots_.size(); ++k) {
        if (!active_[k] || (soft_ && soft_->contains(static_cast<int>(k)))) continue;
        pairs_and_schedule(static_cast<int>(k), t);
    }
    if (soft_) take_exits(state);
}

double EventStepping::resting_fraction(const SimulationState& state) const {
    // Still shot (slower than kHandOverSpeed) touching a surface or another still shot, over the
    // active ones. Neighbours by a sweep along x over the still shot sorted by x.
    const double reach = 2.0 * R_max_ * (1.0 + kContactSlack);  // the sweep's window; each pair is checked at its own
    std::size_t active = 0;
    std::vector<std::pair<double, std::size_t>> still;
    for (std::size_t k = 0; k < state.shots.size(); ++k) {
        if (!state.shots.active[k]) continue;
        ++active;
        if (state.shots.velocity(k).norm() < kHandOverSpeed) still.emplace_back(state.shots.x[k], k);
    }
    if (active == 0 || static_cast<double>(still.size()) <= kHandOverFraction * static_cast<double>(active)) return 0.0;
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

bool EventStepping::touches_surface(const Vec3& p, double R) const {
    for (const Component& comp : model_->components) {
        if (comp.kinematics.moves()) continue;  // nothing rests on a vibrating plate or a turning part
        MeshCollider::Closest closest;
        MeshCollider::QueryCounters counters;
        if (comp.collider->closest_within(comp.kinematics.rest.to_component(p), R * (1.0 + kContactSlack), closest, counters)) return true;
    }
    return false;
}

double EventStepping::key(const Shot& s) const { return std::min({s.wall.time, s.pair_time, s.box_until}); }

void EventStepping::schedule(int i) { queue_.set(i, key(shots_[static_cast<std::size_t>(i)])); }

void EventStepping::process(int i, SimulationState& state, std::vector<ImpactRecord>& impacts) {
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

void EventStepping::set_flight(int i, const Vec3& p, const Vec3& v, double t, Motion motion, const Vec3& support) {
    start_motion(shots_[static_cast<std::size_t>(i)], p, v, t, motion, g_, box_travel_, support);
}

Vec3 EventStepping::position(int i, double t) const {
    if (soft_ && soft_->contains(i)) return soft_->position(i, t);
    return motion_position(shots_[static_cast<std::size_t>(i)], walls_, t);
}

Vec3 EventStepping::velocity(int i, double t) const {
    if (soft_ && soft_->contains(i)) return soft_->velocity(i, t);
    return motion_velocity(shots_[static_cast<std::size_t>(i)], walls_, t);
}

void EventStepping::predict(int i, double t) {
    predict_wall(i, t);
    renew_box(i, t);
    pairs_and_schedule(i, t);
}

void EventStepping::pairs_and_schedule(int i, double t) {
    const bool joins_pile = pairs_.predict(i, t, shots_, active_, queue_, stats_);
    offer_to_pool(i);
    if (joins_pile) {
        // Pressed into a pile (shot in sustained contact or asleep): it joins the pile's sustained
        // contact, which resolves it with the others substep by substep.
        set_flight(i, position(i, t), velocity(i, t), t, Motion::sustained);
        predict(i, t);
        return;
    }
    schedule(i);
}

void EventStepping::predict_wall(int i, double t) {
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
        case Motion::soft:  // the pool finds its contacts
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

void EventStepping::renew_box(int i, double t) {
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

// ---------------------------------------------------------------------------------------------
// Collisions

void EventStepping::collide_wall(int i, double t, SimulationState& state, std::vector<ImpactRecord>& impacts) {
    Shot& s = shots_[static_cast<std::size_t>(i)];
    const WallKind kind = s.wall.kind;
    switch (kind) {
        case WallKind::none:  // the end of a searched window: search the next (same flight)
            ++stats_.box_renewals;
            s.window_travel = std::min(kMaxWindowTravel * s.radius_m, 2.0 * s.window_travel);
            predict(i, t);
            return;
        case WallKind::leave: lose(i, t, state, false); return;
        case WallKind::sink: collect(i, state, static_cast<std::size_t>(s.wall.component)); return;
        case WallKind::launch: launch(i, t, state); return;
        case WallKind::substep: substep(i, t, state, impacts); return;
        case WallKind::contact: break;
    }
    Vec3 p = position(i, t);
    const Vec3 v = velocity(i, t);
    if (!std::isfinite(p.squaredNorm() + v.squaredNorm())) {
        lose(i, t, state, true);
        return;
    }
    WallEvent w = s.wall;
    const auto c = static_cast<std::size_t>(w.component);
    const Component& comp = model_->components[c];
    if (comp.solid && w.mesh_triangle >= 0 && walls_.put_out_of_solid(c, s.radius_m, t, w, p)) {
        // The centre was inside the solid (it reached its surface from within): put back out
        // through the face it lies behind; never a rebound that keeps it inside.
        ++state.health.deep_penetrations;
        ++state.health.mesh_overlap_corrections;
    } else if (w.overlapping) {
        // Found inside the surface (an approximated rider, a rounding): moved out, no energy added.
        p += w.depth * w.normal;
        if (w.depth > contact::kOverlapWorthCounting * s.radius_m) ++state.health.mesh_overlap_corrections;
        if (w.depth > contact::kDeepPenetration * s.radius_m) ++state.health.deep_penetrations;
    }
    const Vec3& n = w.normal;
    const Vec3& vs = w.surface_velocity;
    const double approach = -(v - vs).dot(n);
    // Soft scheme: an impact, or a touch on a moving surface that approaches or that the surface
    // presses (a landing on the vibrating plate), is a soft contact, integrated by the pool.
    if (soft_ && (contact::is_impact(approach, impact_speed_) ||
                  (comp.kinematics.moves() && (approach > resting_speed_ || (w.surface_acceleration - g_).dot(n) > 0.0)))) {
        to_pool(i, t, p, v, std::max(0.0, approach), comp.law->soft(), state, impacts);
        return;
    }
    if (approach > resting_speed_) {
        // A rebound, followed exactly however slow (down to the resting speed). Only an approach at
        // least the impact speed is an impact (logged); a slower one is a slow contact, counted once
        // if it ends a flight, like time stepping's (which stops such a shot instead of following it).
        const bool impact = contact::is_impact(approach, impact_speed_);
        const Pose pose = comp.kinematics.pose(epoch_, t);
        const ContactSite site{i, w.component, w.mesh_triangle, &pose, w.point, absolute_seconds(t), 0.0};
        const contact::SurfaceContactResponse r = comp.law->impact(
            surface_input(*model_, state.shots, site, v, vs, n, impact, 0.0, 0.0, instant_contact_state(contact_scratch_, *model_, c)),
            law_state(state, c));
        if (impact) {
            record_impact(*model_, state, impacts, absolute_seconds(t), i, w.component, w.triangle, pose, w.point, v, w.surface_velocity,
                          r);
            s.in_flight = true;  // sent off by an impact (time stepping's rule: whatever the rebound)
        } else {
            if (s.in_flight) ++state.slow_contacts_per_component[c];
            s.in_flight = false;
        }
        if (w.face) {
            // Riding (pitfall 1): the chatter sequence ends in a ride instead of a Zeno sequence.
            const double closing = (w.surface_acceleration - g_).dot(n);
            if (contact::rebound_rides(closing, r.vn_out, resting_speed_)) {
                start_ride(i, t, w, p, r.v_shot);
                return;
            }
        }
        // A rebound slower than the resting speed is no rebound: sustained contact, sliding along n
        // (a graze if the surface does not press the shot).
        if (r.vn_out < resting_speed_ && !w.face) {
            touch(i, t, w, p, r.v_shot - (r.v_shot - vs).dot(n) * n);
            return;
        } else {
            set_flight(i, p, r.v_shot, t, Motion::flying);
        }
        predict(i, t);
        return;
    }
    // Slower than the resting speed: sustained contact from here (riding on the plate), or a graze.
    // A slow contact if it ends a flight (counted once; a graze read again is not).
    if (s.in_flight && !(t - s.graze_at < kCollapseWindow)) ++state.slow_contacts_per_component[c];
    const Vec3 v_kept = v + std::max(0.0, approach) * n;
    if (w.face) {
        start_ride(i, t, w, p, v_kept);
        return;
    }
    touch(i, t, w, p, v_kept);
}

void EventStepping::touch(int i, double t, const WallEvent& w, const Vec3& p, const Vec3& v_kept) {
    // Pressed onto the surface (gravity, or the surface accelerating into the shot): sustained
    // contact, sliding along it. Otherwise (a side wall, a ceiling) nothing holds the shot there:
    // it grazes on in free flight, where every surface is searched, however fast it moves.
    // Grazes that keep following each other within the TC window (a shot wedged between surfaces,
    // or skimming a moving one) would crawl a hair at a time: after a few, sustained contact.
    // (One or two come right after a graze: the same touch read again a hair later.)
    Shot& s = shots_[static_cast<std::size_t>(i)];
    const bool pressed = (w.surface_acceleration - g_).dot(w.normal) > 0.0;
    s.quick_grazes = t - s.graze_at < kCollapseWindow ? s.quick_grazes + 1 : 0;
    if (!pressed && s.quick_grazes < kMaxQuickGrazes) {
        ++stats_.grazes;
        s.graze_at = t;
        s.in_flight = true;
        set_flight(i, p, v_kept, t, Motion::flying);
    } else {
        s.in_flight = false;
        set_flight(i, p, v_kept, t, Motion::sustained, w.normal);
    }
    predict(i, t);
}

void EventStepping::start_ride(int i, double t, const WallEvent& w, const Vec3& p, const Vec3& v_after) {
    Shot& s = shots_[static_cast<std::size_t>(i)];
    const VibratingPlane& plane = walls_.face(static_cast<std::size_t>(w.component)).plane;
    const Vec3& n = w.normal;
    const double k = plane.axis.dot(n);
    const double w2a = plane.amplitude_m * plane.angular_frequency() * plane.angular_frequency() * k;
    if (!(w2a > 0.0)) {  // a plate moving sideways only: no ride, sustained contact
        set_flight(i, p, v_after, t, Motion::sustained);
        predict(i, t);
        return;
    }
    if (!((w.surface_acceleration - g_).dot(n) > 0.0)) {
        // The plate pulls away faster than gravity: nothing holds the shot on it. It leaves with the
        // plate's normal velocity (the approach removed) and the gap opens at once; riding until the
        // plate next presses would carry it for most of a period and launch it at the plate's peak.
        set_flight(i, p, v_after, t, Motion::flying);
        predict(i, t);
        return;
    }
    ++stats_.rides;
    s.in_flight = false;
    const Vec3 rel = v_after - w.surface_velocity;
    s.ride_component = w.component;
    s.ride_start = t;
    s.ride_point = p;
    s.ride_normal = n;
    s.ride_tangential = rel - rel.dot(n) * n;
    // The plate's acceleration along n is -A w^2 k sin(phase); it presses the shot while that
    // exceeds g.n, i.e. until sin(phase) rises through eps = -g.n / (A w^2 k).
    const double to_release = seconds_to_release(plane.phase(t), -g_.dot(n) / w2a, plane.angular_frequency());
    const double launch_time = t + to_release + kReleaseDelayPeriods / plane.frequency_hz;
    set_flight(i, p, s.ride_tangential, t, Motion::riding);
    s.wall = WallEvent{};
    s.wall.time = launch_time;
    s.wall.kind = launch_time < kInf ? WallKind::launch : WallKind::none;
    s.wall.component = w.component;
    renew_box(i, t);
    pairs_and_schedule(i, t);
}

void EventStepping::launch(int i, double t, SimulationState& state) {
    Shot& s = shots_[static_cast<std::size_t>(i)];
    const VibratingPlane& plane = walls_.face(static_cast<std::size_t>(s.ride_component)).plane;
    // The shot left the plate at the release, kReleaseDelayPeriods before this event
    // (plate_release.h): it flies from the plate's state there.
    const double delay = kReleaseDelayPeriods / plane.frequency_hz;
    const double t_release = t - delay;
    const Vec3 v_plate = plane.velocity(t_release);
    // Coulomb friction over the ride: the normal impulse per unit mass is what the plate gave the
    // shot beyond gravity, and the tangential slip loses f times that (not below zero).
    const double impulse =
        std::max(0.0, (v_plate - plane.velocity(s.ride_start)).dot(s.ride_normal) - g_.dot(s.ride_normal) * (t_release - s.ride_start));
    // Through the pair's law: its sustained contact with the plate pressing the shot by
    // impulse / ride on average over the ride.
    const double ride = t_release - s.ride_start;
    const auto c = static_cast<std::size_t>(s.ride_component);
    const Component& comp = model_->components[c];
    const Pose pose = comp.kinematics.pose(epoch_, s.ride_start);
    const ContactSite site{
        i, s.ride_component, -1, &pose, position(i, s.ride_start) - s.radius_m * s.ride_normal, absolute_seconds(s.ride_start), 0.0};
    const Vec3 v0 = plane.velocity(s.ride_start);
    const contact::SurfaceContactResponse r =
        comp.law->sustain(surface_input(*model_, state.shots, site, v0 + s.ride_tangential, v0, s.ride_normal, false,
                                        ride > 0.0 ? impulse / ride : 0.0, ride, instant_contact_state(contact_scratch_, *model_, c)),
                          law_state(state, c));
    const Vec3 tangential = r.v_shot - v0 - (r.v_shot - v0).dot(s.ride_normal) * s.ride_normal;
    const FlightState flight = after_release({position(i, t_release), v_plate + tangential}, g_, delay);
    s.in_flight = true;
    set_flight(i, flight.position_m, flight.velocity_m_per_s, t, Motion::flying);
    predict(i, t);
}

void EventStepping::substep(int i, double t, SimulationState& state, std::vector<ImpactRecord>& impacts) {
    ++stats_.substeps;
    const Vec3 p = position(i, t), v = velocity(i, t);
    if (!std::isfinite(p.squaredNorm() + v.squaredNorm())) {
        lose(i, t, state, true);
        return;
    }
    const SustainedContact::Next next = sustained_.end_of_substep(i, t, p, v, epoch_, shots_, active_, pairs_, walls_, state, impacts);
    if (next.motion == Motion::sleeping) ++stats_.sleeps;
    set_flight(i, next.position_m, next.velocity_m_per_s, t, next.motion, next.support);
    predict(i, t);
}

void EventStepping::collide_pair(int i, int j, double t, SimulationState& state, std::vector<ImpactRecord>& impacts) {
    Shot& a = shots_[static_cast<std::size_t>(i)];
    Shot& b = shots_[static_cast<std::size_t>(j)];
    const bool a_slept = a.motion == Motion::sleeping, b_slept = b.motion == Motion::sleeping;
    Vec3 pi = position(i, t), pj = position(j, t);
    Vec3 vi = velocity(i, t), vj = velocity(j, t);
    const Vec3 r = pj - pi;
    const double d = r.norm();
    bool slow = false, impact = false;
    const Vec3 n = d > 0.0 ? Vec3(r / d) : Vec3(Vec3::Zero());  // from i towards j
    if (d > 0.0) {
        const double touch = a.radius_m + b.radius_m;
        if (d < touch) {
            // Overlap (a rider's approximated path, or a rounding): removed symmetrically, positions only.
            const double depth = touch - d;
            if (depth > kTouchDistance * touch) {
                pi -= 0.5 * depth * n;
                pj += 0.5 * depth * n;
                if (depth > contact::kOverlapWorthCounting * std::min(a.radius_m, b.radius_m)) ++state.health.shot_overlap_corrections;
            }
        }
        const double approach = -(vj - vi).dot(n);
        if (soft_ && contact::is_impact(approach, impact_speed_)) {
            // Soft scheme: both shot are the pool's from their touch (positions as they are: a
            // soft contact's overlap is its physics).
            const Vec3 p_i = position(i, t), p_j = position(j, t);
            to_pool(i, t, p_i, vi, approach, model_->shot_shot_law->soft(), state, impacts);
            to_pool(j, t, p_j, vj, approach, model_->shot_shot_law->soft(), state, impacts);
            return;
        }
        if (approach > 0.0) {
            impact = contact::is_impact(approach, impact_speed_);
            if (!impact && (a.in_flight || b.in_flight)) ++state.shot_shot_slow_contacts;
            const bool right_after = t - a.last_pair_time < kCollapseWindow || t - b.last_pair_time < kCollapseWindow;
            const contact::ShotShotMode mode = contact::shot_shot_mode(approach, resting_speed_, right_after);
            slow = mode == contact::ShotShotMode::sustained;
            if (mode == contact::ShotShotMode::collapse_guard) ++stats_.collapse_guards;
            const contact::ShotShotResponse resp = model_->shot_shot_law->respond(
                shot_shot_input(*model_, state.shots, i, j, vi, vj, n, mode, (pj - pi).norm(), absolute_seconds(t)));
            vi = resp.v_i;
            vj = resp.v_j;
            if (impact) ++state.shot_shot_impacts;
        }
    }
    if (d > 0.0) a.in_flight = b.in_flight = impact;
    a.last_pair_time = b.last_pair_time = t;
    a.last_partner = j;
    b.last_partner = i;
    const auto after = [&](const Shot& s) { return slow || s.motion == Motion::sustained ? Motion::sustained : Motion::flying; };
    // A contact slower than the resting speed leaves the upper shot resting on the lower one.
    set_flight(i, pi, vi, t, after(a), slow ? Vec3(-n) : Vec3(Vec3::Zero()));
    set_flight(j, pj, vj, t, after(b), slow ? n : Vec3(Vec3::Zero()));
    if (contact_state_) {  // knocked off its support: its contacts have ended
        if (a.motion == Motion::flying) state.contacts.end_all(i);
        if (b.motion == Motion::flying) state.contacts.end_all(j);
    }
    predict(i, t);
    predict(j, t);
    if (a_slept) wake_neighbours(i, t);
    if (b_slept) wake_neighbours(j, t);
}

void EventStepping::wake_neighbours(int i, double t) {
    wake_stack_.clear();
    woken_.clear();
    wake_stack_.push_back(i);
    while (!wake_stack_.empty()) {
        const int k = wake_stack_.back();
        wake_stack_.pop_back();
        const Vec3 p = position(k, t);
        const Vec3 reach = Vec3::Constant(shots_[static_cast<std::size_t>(k)].radius_m + R_max_ + kContactSlack * R_max_);
        pairs_.overlapping(p - reach, p + reach, neighbours_);
        const std::size_t first_woken = woken_.size();
        for (const int j : neighbours_) {
            Shot& o = shots_[static_cast<std::size_t>(j)];
            if (j == k || !active_[static_cast<std::size_t>(j)] || o.motion != Motion::sleeping) continue;
            set_flight(j, o.path.p0, Vec3::Zero(), t, Motion::sustained);
            woken_.push_back(j);
        }
        // Predicted only now: predicting reuses neighbours_.
        for (std::size_t w = first_woken; w < woken_.size(); ++w) {
            predict(woken_[w], t);
            wake_stack_.push_back(woken_[w]);
        }
    }
    woken_.clear();
}

void EventStepping::collect(int i, SimulationState& state, std::size_t sink) {
    ++state.collected_per_sink[sink];
    retire(i, state);
}

void EventStepping::lose(int i, double t, SimulationState& state, bool non_finite) {
    const auto k = static_cast<std::size_t>(i);
    if (non_finite) {
        ++state.health.non_finite;
    } else {
        ++state.health.shot_lost;
        LostShot l;
        l.shot = i;
        l.time_s = absolute_seconds(t);
        l.position_m = position(i, t);
        const Trajectory& flight = shots_[k].path;  // exact since the shot's last event
        l.radius_m = shots_[k].radius_m;
        diagnose_loss(*model_, epoch_, flight, l.radius_m, flight.t0, t, l);
        if (l.cause == LossCause::engine_error) ++state.health.engine_errors;
        state.lost.push_back(l);
    }
    retire(i, state);
}

void EventStepping::retire(int i, SimulationState& state) {
    const auto k = static_cast<std::size_t>(i);
    if (contact_state_) state.contacts.end_all(i);
    active_[k] = 0;
    state.shots.active[k] = 0;
    pairs_.remove(i);
    Shot& s = shots_[k];
    s.wall = WallEvent{};
    s.wall.time = kInf;
    s.pair_time = kInf;
    s.box_until = kInf;
    ++s.version;
    queue_.set(i, kInf);
}

}  // namespace peensim

namespace peensim {

// ---------------------------------------------------------------------------------------------
// The soft scheme's pool

void EventStepping::to_pool(int i, double t, const Vec3& p, const Vec3& v, double approach, const contact::SoftLaw* law,
                            SimulationState& state, std::vector<ImpactRecord>& impacts) {
    if (contact_state_) state.contacts.end_all(i);
    soft_->join(i, t, p, v, state.shots.spin(static_cast<std::size_t>(i)), approach, law, *this, state, impacts, exits_, stats_);
    take_exits(state);
}

void EventStepping::take_exits(SimulationState& state) {
    if (exits_.empty()) return;
    const double t = soft_->time();
    // Each set up first, then predicted, so that their predictions see one another.
    for (const SoftExit& e : exits_) {
        const int i = e.shot;
        Shot& s = shots_[static_cast<std::size_t>(i)];
        switch (e.to) {
            case SoftExit::To::lost: break;
            case SoftExit::To::flight:
                s.in_flight = true;
                set_flight(i, e.position_m, e.velocity_m_per_s, t, Motion::flying);
                break;
            case SoftExit::To::rest:
                s.in_flight = false;
                set_flight(i, e.position_m, e.velocity_m_per_s, t, Motion::sustained, e.support);
                break;
        }
    }
    // Copied: a prediction may hand a shot to the pool again (and fill exits_ anew).
    std::vector<SoftExit> leaving;
    leaving.swap(exits_);
    for (const SoftExit& e : leaving) {
        if (e.to == SoftExit::To::lost) {
            lose(e.shot, t, state, true);
            continue;
        }
        if (soft_->contains(e.shot)) continue;
        predict_wall(e.shot, t);
        renew_box(e.shot, t);
        shots_[static_cast<std::size_t>(e.shot)].pair_time = kInf;
        schedule(e.shot);
    }
    for (const SoftExit& e : leaving)
        if (e.to != SoftExit::To::lost && !soft_->contains(e.shot)) pairs_and_schedule(e.shot, t);
    leaving.clear();
    if (exits_.empty()) leaving.swap(exits_);  // keep the capacity
}

void EventStepping::offer_to_pool(int i) {
    if (!soft_) return;
    for (const int member : pairs_.soft_neighbours()) soft_->add_candidate(member, i);
}

void EventStepping::set_box(int shot, const Vec3& lo, const Vec3& hi) {
    Shot& s = shots_[static_cast<std::size_t>(shot)];
    s.box_lo = lo;
    s.box_hi = hi;
    s.box_until = kInf;
    pairs_.set_box(shot, lo, hi);
}

bool EventStepping::path_of(int shot, double t, Trajectory& out) const {
    const auto k = static_cast<std::size_t>(shot);
    if (k >= shots_.size() || !active_[k]) return false;
    const Shot& s = shots_[k];
    if (s.motion == Motion::riding) {
        out = Trajectory{position(shot, t), velocity(shot, t), Vec3::Zero(), t};
        return true;
    }
    out = s.path;
    return true;
}

void EventStepping::joined(int shot, double t) {
    Shot& s = shots_[static_cast<std::size_t>(shot)];
    s.motion = Motion::soft;
    ++s.version;  // pair events predicted against its flight are stale
    s.wall = WallEvent{};
    s.wall.time = kInf;
    s.pair_time = kInf;
    s.partner = -1;
    s.in_flight = false;
    s.path.t0 = t;
    queue_.set(shot, kInf);
}

void EventStepping::moved(int shot, const Vec3& p, const Vec3& v, double t) {
    shots_[static_cast<std::size_t>(shot)].path = Trajectory{p, v, g_, t};
}

}  // namespace peensim
