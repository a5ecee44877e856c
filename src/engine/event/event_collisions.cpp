// What an event does: a rebound from a surface (or a touch, a ride, a graze), the end of a ride or
// of a substep of sustained contact, a shot-shot collision, a shot collected or lost. The event
// core's (event_core.h) collision half.
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/float_limits.h"
#include "engine/event/event_core.h"
#include "engine/impact_recording.h"
#include "engine/law_input.h"
#include "engine/loss_diagnosis.h"
#include "kernels/plate_release.h"

namespace peensim {

namespace {

constexpr double kMaxWindowTravel = 64.0;  // radii: windows double up to this while a flight finds nothing
constexpr double kCollapseWindow = 1e-6;   // s, TC rule: a shot-shot collision this soon after one is elastic
constexpr int kMaxQuickGrazes = 4;         // grazes each within kCollapseWindow of the last, then sustained contact

}  // namespace

void EventCore::collide_wall(int i, double t, SimulationState& state, std::vector<ImpactRecord>& impacts) {
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
    // A contact the pool asks for is the pool's (in the soft scheme: every impact, and more).
    if (pool_ && pool_->take_wall_contact(i, t, p, v, approach, comp, w, state, impacts)) return;
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

void EventCore::touch(int i, double t, const WallEvent& w, const Vec3& p, const Vec3& v_kept) {
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

void EventCore::start_ride(int i, double t, const WallEvent& w, const Vec3& p, const Vec3& v_after) {
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

void EventCore::launch(int i, double t, SimulationState& state) {
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

void EventCore::substep(int i, double t, SimulationState& state, std::vector<ImpactRecord>& impacts) {
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

void EventCore::collide_pair(int i, int j, double t, SimulationState& state, std::vector<ImpactRecord>& impacts) {
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
        if (pool_ && pool_->take_pair_contact(i, j, t, vi, vj, approach, state, impacts)) return;
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

void EventCore::wake_neighbours(int i, double t) {
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

void EventCore::collect(int i, SimulationState& state, std::size_t sink) {
    ++state.collected_per_sink[sink];
    retire(i, state);
}

void EventCore::lose(int i, double t, SimulationState& state, bool non_finite) {
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

void EventCore::retire(int i, SimulationState& state) {
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
