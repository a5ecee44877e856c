#include "engine/time_stepping.h"

#include <algorithm>
#include <cmath>

#include "collision/surface_clearance.h"
#include "engine/contact_time.h"
#include "engine/impact_recording.h"
#include "engine/law_input.h"
#include "engine/moving_mesh_gap.h"
#include "kernels/closest_point.h"
#include "kernels/plate_release.h"
#include "kernels/vibrating_plane_toi.h"

namespace peensim {

namespace {

double s_velocity_norm(const ShotArrays& s, std::size_t i) { return std::sqrt(s.vx[i] * s.vx[i] + s.vy[i] * s.vy[i] + s.vz[i] * s.vz[i]); }

// Contact passes of one shot within one step before giving up (health: unresolved_contacts). A
// shot chattering on the plate is followed rebound by rebound down to contact::kRideSpeed: ~70
// rebounds (C = 0.9) from 2 m/s, the fastest the plate catches within a step at the default travel,
// ~700 at C = 0.99. Only a chattering shot takes more than two passes.
constexpr int kMaxContactPasses = 1024;
constexpr double kTouchTimeTolerance = 1e-14;  // s, precision of sampled touch times
// Bound on how far a shot can move relative to a component in one step, in units of the eq. 7
// travel: the shot's own travel (1) plus the surface's (1: V_max includes surface speeds). A shot
// kicked within a step can go further; its skip counters are reset at every kick.
constexpr double kMaxRelativeTravelPerStep = 2.0;
// -, the most gravity may add to a shot's speed in one step, as a fraction of the impact speed (5 mm/s
// at the default 5 cm/s: a 0.51 ms step, longer than the 80 us the shipped sonotrodes already impose).
constexpr double kGravityShareOfImpactSpeed = 0.1;
// -, a shot whose gap to a surface is below this fraction of R is touching it (1 nm for 2 mm shot:
// far above the ~1e-17 m roundings of a shot left on a surface, far below any real flight).
constexpr double kTouchingGap = 1e-6;
// How much further than needed a mesh query looks (fraction of R), to learn the distance of a shot
// that misses: it then needs no query until it has moved that much closer.
constexpr double kMemoMargin = 0.5;

}  // namespace

double TimeStepping::step_for(double v_max, double gravity, double travel_m) {
    // 0.5 g dt^2 + v dt = travel, solved in the form that stays exact when g -> 0 or v -> 0.
    return 2.0 * travel_m / (v_max + std::sqrt(v_max * v_max + 2.0 * gravity * travel_m));
}

double TimeStepping::time_step(const Model& model, double v_max) {
    // Gravity, or what bounds a flight's speed gain (drag only ever slows a shot in still air).
    const double g = model.flight_speed_gain_bound_m_per_s2;
    // The smallest shot of a mix sets the travel: a quarter of its radius.
    const double dt = step_for(v_max, g, model.travel_fraction * model.min_shot_radius_m);
    return g > 0.0 ? std::min(dt, kGravityShareOfImpactSpeed * model.impact_speed_m_per_s / g) : dt;
}

TimeStepping::TimeStepping(std::shared_ptr<const Model> model)
    : model_(std::move(model)),
      // Fat margin of the shot broad phase: one radius, about four steps of travel at the default
      // quarter-radius step (measured best in the reference notes: fewer re-insertions, few extra pairs).
      pairs_(model_->shot_count, model_->max_shot_radius_m, model_->min_shot_radius_m),
      parabola_(model_->flight->is_parabola()),
      contact_state_(uses_contact_state(*model_)) {
    pose_end_.resize(model_->components.size());
    n_shots_ = static_cast<std::size_t>(model_->shot_count);
    skip_until_.assign(model_->components.size() * n_shots_, 0);
    max_relative_travel_ = kMaxRelativeTravelPerStep * model_->travel_fraction * model_->min_shot_radius_m;
    memo_.assign(model_->components.size() * n_shots_, DistanceMemo{});
    memo_margin_ = kMemoMargin * model_->min_shot_radius_m;
    for (const Component& c : model_->components) {
        // The largest query radius a step uses for this component (see handle_component).
        const double travel = model_->travel_fraction * model_->min_shot_radius_m;
        max_query_radius_.push_back(model_->max_shot_radius_m +
                                    (c.kinematics.amplitude_m > 0.0 ? 2.0 * c.kinematics.amplitude_m + travel : 0.0));
        gates_.push_back(std::make_unique<const DistanceGate>(
            DistanceGate::for_shot(*c.mesh, model_->max_shot_radius_m, 2.0 * c.kinematics.amplitude_m)));
        sharp_.emplace_back(*gates_.back(), *c.collider, max_query_radius_.back());
    }
    last_touch_.assign(static_cast<std::size_t>(model_->shot_count), 0.0);
    last_touch_component_.assign(static_cast<std::size_t>(model_->shot_count), -1);
    kicked_by_shot_.assign(static_cast<std::size_t>(model_->shot_count), 0);
    touched_.assign(static_cast<std::size_t>(model_->shot_count), 0);
}

void TimeStepping::state_changed() {
    std::fill(skip_until_.begin(), skip_until_.end(), 0);
    std::fill(memo_.begin(), memo_.end(), DistanceMemo{});
}

void TimeStepping::fit_shots(std::size_t n) {
    if (n <= last_touch_.size()) return;
    if (n > n_shots_) {
        // The per-component tables are laid out with a stride: doubled, they are copied rarely.
        const std::size_t stride = std::max(n, 2 * n_shots_), components = model_->components.size();
        std::vector<std::uint64_t> skip(components * stride, 0);
        std::vector<DistanceMemo> memo(components * stride);
        for (std::size_t c = 0; c < components; ++c)
            for (std::size_t i = 0; i < n_shots_; ++i) {
                skip[c * stride + i] = skip_until_[c * n_shots_ + i];
                memo[c * stride + i] = memo_[c * n_shots_ + i];
            }
        skip_until_.swap(skip);
        memo_.swap(memo);
        n_shots_ = stride;
    }
    last_touch_.resize(n, 0.0);
    last_touch_component_.resize(n, -1);
    kicked_by_shot_.resize(n, 0);
    touched_.resize(n, 0);
    pairs_.grow(static_cast<int>(n));
}

void TimeStepping::shots_added(SimulationState& state, const std::vector<int>& shots) {
    fit_shots(state.shots.size());
    for (const int i : shots) {
        // A reused slot's memos describe the shot that was there.
        const auto k = static_cast<std::size_t>(i);
        for (std::size_t c = 0; c < model_->components.size(); ++c) memo_[c * n_shots_ + k] = DistanceMemo{};
        forget_clearances(k);
    }
}

void TimeStepping::advance(SimulationState& state, double t_end_s, double /*pause_at_s*/, std::vector<ImpactRecord>& impacts) {
    const double now = state.time.seconds();
    const double remaining = t_end_s - now;
    if (!(remaining > 0.0)) return;
    const double v_max = std::max(state.fastest_shot_m_per_s, model_->peak_surface_speed_m_per_s);
    double dt = time_step(*model_, v_max);
    if (!(dt > 0.0) || !std::isfinite(dt) || dt >= remaining * (1.0 - 1e-9)) dt = remaining;
    step_ = state.steps;
    fit_shots(state.shots.size());  // an edit may have added shot
    // Every sustained contact is resolved once a step: one not found again in this step has ended.
    stamp_ = contact_state_ ? state.contacts.begin_resolution() : 0;
    // A state made before the flags existed (or by hand in a test) starts with every shot at rest.
    if (state.shots.in_flight.size() != state.shots.size()) state.shots.in_flight.assign(state.shots.size(), 0);
    if (state.slow_contacts_per_component.size() != model_->components.size())
        state.slow_contacts_per_component.resize(model_->components.size(), 0);

    {
        StageTimer timer(stats_, Stage::kinematics);
        t0_ = state.time;
        for (std::size_t c = 0; c < model_->components.size(); ++c) pose_end_[c] = model_->components[c].kinematics.pose(t0_, dt);
    }
    integrate(state, dt);
    // Walls first: a shot must never end a step inside a surface. Then shot-shot contacts, and
    // walls again for the shot those kicked (their rest of the step changed).
    resolve_mesh_contacts(state, dt, impacts, /*only_kicked=*/false);
    resolve_shot_pairs(state, dt);
    resolve_mesh_contacts(state, dt, impacts, /*only_kicked=*/true);
    note_free_flights(state);
    check_health(state);
    if (contact_state_) state.contacts.end_unseen(stamp_);

    state.time.advance(dt);
    if (t_end_s - state.time.seconds() < 1e-12 * t_end_s) {
        // Land exactly on the end time (the compensated sum may be an ulp short).
        state.time.hi = t_end_s;
        state.time.lo = 0.0;
    }
    ++state.steps;
}

Vec3 TimeStepping::arc_acceleration(const ShotArrays& s, std::size_t i, const Vec3& p, const Vec3& v) const {
    return parabola_ ? model_->gravity_m_per_s2 : shot_size(*model_, s, i).flight->acceleration(p, v);
}

void TimeStepping::fly(ShotArrays& s, std::size_t i, const Vec3& p, const Vec3& v, double dt) const {
    Vec3 p_end = p, v_end = v;
    shot_size(*model_, s, i).flight->advance(p_end, v_end, dt);
    s.set_position(i, p_end);
    s.set_velocity(i, v_end);
}

void TimeStepping::integrate(SimulationState& state, double dt) {
    StageTimer timer(stats_, Stage::integrate);
    ShotArrays& s = state.shots;
    if (!parabola_) {
        // Another flight model (air drag): each shot advanced through it. Lost shot keep still.
        std::uint64_t active = 0;
        for (std::size_t i = 0; i < s.size(); ++i) {
            if (!s.active[i]) continue;
            fly(s, i, s.position(i), s.velocity(i), dt);
            ++active;
        }
        clear_step_marks();
        state.shot_steps += active;
        return;
    }
    const Vec3 g = model_->gravity_m_per_s2;
    const double hx = 0.5 * g.x() * dt * dt, hy = 0.5 * g.y() * dt * dt, hz = 0.5 * g.z() * dt * dt;
    const std::size_t n = s.size();
    std::uint64_t active = 0;
    for (std::size_t i = 0; i < n; ++i) {
        // Exact free flight under gravity (eq. 1). Lost shot keep still.
        const double on = s.active[i];
        s.x[i] += on * (s.vx[i] * dt + hx);
        s.y[i] += on * (s.vy[i] * dt + hy);
        s.z[i] += on * (s.vz[i] * dt + hz);
        s.vx[i] += on * g.x() * dt;
        s.vy[i] += on * g.y() * dt;
        s.vz[i] += on * g.z() * dt;
        active += s.active[i];
    }
    clear_step_marks();
    state.shot_steps += active;
}

void TimeStepping::clear_step_marks() {
    std::fill(last_touch_.begin(), last_touch_.end(), 0.0);
    std::fill(last_touch_component_.begin(), last_touch_component_.end(), -1);
    std::fill(kicked_by_shot_.begin(), kicked_by_shot_.end(), 0);
    std::fill(touched_.begin(), touched_.end(), 0);
}

void TimeStepping::resolve_shot_pairs(SimulationState& state, double dt) {
    ShotArrays& s = state.shots;
    {
        StageTimer timer(stats_, Stage::shot_broadphase);
        pairs_.update(s.x.data(), s.y.data(), s.z.data(), s.active.data());
    }
    StageTimer timer(stats_, Stage::shot_contacts);
    const contact::ShotShotLaw& law = *model_->shot_shot_law;
    // Only pairs that overlap now, in a fixed order: the result must not depend on the history
    // inside Bullet's pair cache (a resumed run continues exactly like an uninterrupted one).
    touching_.clear();
    pairs_.for_each_pair([&](int a, int b) {
        const auto i = static_cast<std::size_t>(a), j = static_cast<std::size_t>(b);
        if (!s.active[i] || !s.active[j]) return;
        const double D = shot_radius(*model_, s, i) + shot_radius(*model_, s, j);  // m, centre distance at contact
        if ((s.position(j) - s.position(i)).squaredNorm() < D * D) touching_.emplace_back(a, b);
    });
    std::sort(touching_.begin(), touching_.end());
    for (const auto& [a, b] : touching_) {
        const auto i = static_cast<std::size_t>(a), j = static_cast<std::size_t>(b);
        const double D = shot_radius(*model_, s, i) + shot_radius(*model_, s, j);  // m
        const Vec3 r1 = s.position(j) - s.position(i);
        const double d2 = r1.squaredNorm();
        if (d2 >= D * D) continue;
        const Vec3 vi = s.velocity(i), vj = s.velocity(j), dv = vj - vi;
        // Both shot fall alike, so their relative motion is linear: |r1 - dv s|^2 = D^2, s before the end.
        const double u_lo = std::max(last_touch_[i], last_touch_[j]);
        const double u = first_touch_quadratic(d2 - D * D, -2.0 * r1.dot(dv), dv.squaredNorm(), u_lo, dt).value_or(dt);
        const double back = dt - u;
        const Vec3 rc = r1 - dv * back;
        if (rc.squaredNorm() < 1e-24) continue;  // coincident centres: no normal to act along
        const Vec3 n = rc.normalized();
        const double approach = -dv.dot(n);
        touched_[i] = touched_[j] = 1;
        if (approach > 0.0) {
            const bool impact = contact::is_impact(approach, model_->impact_speed_m_per_s);
            // Time stepping cannot follow a rebound slower than the impact speed: sustained (the
            // approach stops). It has no TC window: a step resolves each pair once.
            const contact::ShotShotMode mode = contact::shot_shot_mode(approach, model_->impact_speed_m_per_s, false);
            const double time_s = t0_.hi + (t0_.lo + u);
            const contact::ShotShotResponse r = law.respond(shot_shot_input(*model_, s, a, b, vi, vj, n, mode, std::sqrt(d2), time_s));
            const Vec3 dvi = r.v_i - vi, dvj = r.v_j - vj;
            // After a velocity change at time u the rest of the flight shifts by dv * (dt - u): exact.
            s.set_velocity(i, r.v_i);
            s.set_velocity(j, r.v_j);
            s.set_position(i, s.position(i) + dvi * back);
            s.set_position(j, s.position(j) + dvj * back);
            last_touch_[i] = last_touch_[j] = u;
            last_touch_component_[i] = last_touch_component_[j] = -1;
            kicked_by_shot_[i] = kicked_by_shot_[j] = 1;
            forget_clearances(i);
            forget_clearances(j);
            if (impact) {
                ++state.shot_shot_impacts;
                state.shots.in_flight[i] = state.shots.in_flight[j] = 1;  // both fly off
            } else {
                // Sustained: one slow contact if either shot was flying (a shot landing on a resting one).
                const bool i_landed = ends_a_flight(state, i), j_landed = ends_a_flight(state, j);
                if (i_landed || j_landed) ++state.shot_shot_slow_contacts;
            }
        }
        // Any overlap left (several contacts in one step) is removed symmetrically, positions only.
        const Vec3 r = s.position(j) - s.position(i);
        const double d = r.norm();
        if (d < D && d > 0.0) {
            const Vec3 push = 0.5 * (D - d) / d * r;
            s.set_position(i, s.position(i) - push);
            s.set_position(j, s.position(j) + push);
            kicked_by_shot_[i] = kicked_by_shot_[j] = 1;
            forget_clearances(i);
            forget_clearances(j);
            if (D - d > contact::kOverlapWorthCounting * std::min(shot_radius(*model_, s, i), shot_radius(*model_, s, j)))
                ++state.health.shot_overlap_corrections;
        }
    }
}

void TimeStepping::forget_clearances(std::size_t shot) {
    for (std::size_t c = 0; c < model_->components.size(); ++c) skip_until_[c * n_shots_ + shot] = 0;
}

void TimeStepping::resolve_mesh_contacts(SimulationState& state, double dt, std::vector<ImpactRecord>& impacts, bool only_kicked) {
    const double laws_before = stats_[Stage::contact_laws];
    const auto start = std::chrono::steady_clock::now();
    const std::size_t n = state.shots.size(), components = model_->components.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (!state.shots.active[i]) continue;
        if (only_kicked && !kicked_by_shot_[i]) continue;
        int pass = 0;
        bool changed = true;
        while (changed && pass < kMaxContactPasses) {
            changed = false;
            for (std::size_t c = 0; c < components; ++c) changed |= handle_component(state, i, c, dt, impacts);
            ++pass;
        }
        if (changed) ++state.health.unresolved_contacts;
    }
    // The loop's time minus what the contact laws took is the time spent finding contacts.
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats_[Stage::mesh_queries] += total - (stats_[Stage::contact_laws] - laws_before);
}

bool TimeStepping::closest_contact(std::size_t component, std::size_t shot, double R, const Vec3& p_world, const Vec3& v_world,
                                   double query_radius, Contact& out) {
    const Component& comp = model_->components[component];
    const Pose& pose = pose_end_[component];
    const Vec3 p = pose.to_component(p_world);
    ++stats_.gate_checks;
    const double distance = sharp_[component].lower_bound(p);
    if (distance > query_radius) {
        // The shot cannot reach this component for a while: skip its checks until then. The
        // clearance is taken against the largest query radius any step may use (a vibrating
        // surface's reach grows with the step, up to twice its amplitude).
        const double clearance = distance - max_query_radius_[component];
        if (clearance > 0.0)
            skip_until_[component * n_shots_ + shot] = step_ + static_cast<std::uint64_t>(clearance / max_relative_travel_);
        return false;
    }
    // The shot's last exact distance to this component bounds its distance now: the distance
    // function is 1-Lipschitz, so it is at least d_then - |p - p_then| (both in the component's frame).
    DistanceMemo& memo = memo_[component * n_shots_ + shot];
    if (memo.distance - (p - memo.where).norm() > query_radius) {
        ++stats_.memo_skips;
        return false;
    }
    ++stats_.bvh_queries;
    // One contact per shot and component: the closest feature. Neighbouring triangles that share the
    // closest edge or vertex give the same point, so spurious normals at internal edges never act.
    // The query looks a little further than needed, to learn the distance of a shot that misses.
    const double look = query_radius + memo_margin_;
    MeshCollider::Closest closest;
    MeshCollider::QueryCounters counters;
    const bool found = comp.collider->closest_within(p, look, closest, counters);
    stats_.triangle_tests += counters.triangles_tested;
    stats_.triangles_returned += counters.triangles_returned;
    memo.where = p;
    memo.distance = found ? closest.distance : look;
    if (!found || closest.distance >= query_radius) return false;
    ++stats_.bvh_hits;
    const TriangleMesh& mesh = *comp.mesh;
    const int best_triangle = closest.triangle;
    const Vec3 best_point = closest.point;
    double d = closest.distance;
    Vec3 n_local;
    const SurfaceClearance clear = comp.solid ? surface_clearance(mesh, true, p, closest) : SurfaceClearance{};
    if (comp.solid && clear.distance_m < 0.0) {
        // The centre is behind a face of a closed part: the nearest-point normal points further
        // in, so the shot is pushed back out through the face it crossed (surface_clearance.h).
        d = clear.distance_m;
        n_local = clear.normal;
    } else if (d > 1e-9 * R) {
        n_local = (p - best_point) / d;
    } else {
        // Centre on the surface: take the face normal on the side the shot came from.
        const auto tt = static_cast<std::size_t>(best_triangle);
        n_local = (mesh.corner(tt, 1) - mesh.corner(tt, 0)).cross(mesh.corner(tt, 2) - mesh.corner(tt, 0)).normalized();
        if (n_local.dot(pose.rotation.transpose() * v_world) > 0.0) n_local = -n_local;
    }
    out.gap = d - R;
    out.normal = pose.rotation * n_local;
    out.point = pose.to_world(best_point);
    out.triangle = mesh.source_facet.empty() ? best_triangle : mesh.source_facet[static_cast<std::size_t>(best_triangle)];
    out.mesh_triangle = best_triangle;
    return true;
}

std::optional<double> TimeStepping::vibrating_touch(const Kinematics& kin, const Contact& contact, const Vec3& p1, const Vec3& v1,
                                                    const Vec3& g, double R, double dt, double u_lo, bool leaving) const {
    // The contact plane found at the step end, vibrating with the sonotrode over the step, against
    // the shot's free-flight arc, solved exactly (vibrating_plane_toi.h) in the step's own time u.
    // Sampling the gap 32 times a period missed grazing touches (the plate catching a shot at
    // the top of its stroke for less than a sample): in the tube at 1 mm / 80 um the floor rate
    // came out 2 % low and its mean speed 2 % high against the exact reference.
    VibratingPlane plane;
    plane.normal = contact.normal;
    plane.axis = kin.axis;
    plane.amplitude_m = kin.amplitude_m;
    plane.frequency_hz = kin.frequency_hz;
    plane.phase_rad = 2.0 * M_PI * t0_.cycle_fraction(kin.frequency_hz) + kin.phase_rad;  // the phase at u = 0
    plane.point_m = contact.point - kin.axis * kin.displacement(t0_, dt);
    const Trajectory path{p1 - v1 * dt + 0.5 * g * dt * dt, v1 - g * dt, g, 0.0};
    PlaneContact at;
    switch (vibrating_plane_toi(path, R, plane, u_lo, dt, at)) {
        case ToiStatus::impact: return at.time;
        // Overlapping at the start of the search: touching now, unless that is the rebound just taken.
        case ToiStatus::overlapping: return leaving ? std::nullopt : std::optional<double>(u_lo);
        case ToiStatus::miss: break;
    }
    return std::nullopt;
}

bool TimeStepping::handle_component(SimulationState& state, std::size_t i, std::size_t c, double dt, std::vector<ImpactRecord>& impacts) {
    const Component& comp = model_->components[c];
    const Kinematics& kin = comp.kinematics;
    const bool vibrating = kin.kind == Kinematics::Kind::vibrating && kin.amplitude_m > 0.0;
    // A vibrating surface may reach a shot within the step and fall back before its end: look
    // as far as it can travel in the step.
    // A vibrating surface may reach a shot within the step and fall back before its end, while the
    // shot moves on: look as far as the surface can travel in the step plus the shot's own travel.
    const double swing = vibrating ? std::min(2.0 * kin.amplitude_m, kin.amplitude_m * kin.angular_frequency() * dt) +
                                         s_velocity_norm(state.shots, i) * dt + 0.5 * model_->flight_speed_gain_bound_m_per_s2 * dt * dt
                                   : 0.0;
    if (step_ < skip_until_[c * n_shots_ + i]) {
        ++stats_.gate_skips;
        return false;
    }
    ShotArrays& s = state.shots;
    const double R = shot_radius(*model_, s, i);
    const Vec3 p1 = s.position(i), v1 = s.velocity(i);
    Contact contact{};
    if (!closest_contact(c, i, R, p1, v1, R + swing, contact)) return false;
    // A shot left exactly on a surface by sustained contact, which no force presses onto it (sliding
    // along a wall, rolling round a chamber), is still touching it, not in free flight: without
    // this its every re-contact (the next facet of a curved wall) would count as a new landing.
    if (contact.gap < kTouchingGap * R) touched_[i] = 1;
    if (contact.gap >= swing && contact.gap >= 0.0) return false;

    StageTimer timer(stats_, Stage::contact_laws);
    // The step's arc, known by its end: the parabola under gravity, or under the flight's
    // acceleration at the step end (air drag: the velocity changes by under 1e-4 of itself in a
    // step, so the arc's centre is off by under 1e-9 R).
    const Vec3 g = arc_acceleration(s, i, p1, v1);
    const Vec3& n = contact.normal;
    const double u_lo = last_touch_[i];
    // A gap of ~0 at u_lo is the rebound from this very component just taken, not a new contact.
    const bool leaving = last_touch_component_[i] == static_cast<int>(c);
    // Gap at time u within the step, with the shot on its free-flight arc and the contact plane
    // moving with the surface.
    std::optional<double> touch;
    std::optional<MovingMeshGap> turning_gap;
    ++stats_.touch_searches;
    if (vibrating) {
        touch = vibrating_touch(kin, contact, p1, v1, g, R, dt, u_lo, leaving);
    } else if (kin.kind == Kinematics::Kind::rotating) {
        // A turning mesh: the true gap, the mesh in its pose at each trial time (moving_mesh_gap.h).
        turning_gap.emplace(comp, t0_, StepArc{p1, v1, g, dt}, R, u_lo, stats_);
        touch = first_touch_sampled(*turning_gap, u_lo, dt, turning_gap->sample_interval(), kTouchTimeTolerance, leaving);
    } else {
        // A static plane: the gap is exactly quadratic in time.
        touch = first_touch_quadratic(contact.gap, -n.dot(v1), 0.5 * n.dot(g), u_lo, dt);
    }
    if (contact.gap < -contact::kDeepPenetration * R) ++state.health.deep_penetrations;
    if (!touch) {
        // No new touch: either no contact at all, or the surface never let go of a shot that just
        // rebounded from it (a slow rebound on an accelerating plate): that shot rides the surface.
        // That is the impact's own contact going on, not the end of a flight: no slow contact.
        if (contact.gap >= 0.0) return false;
        touched_[i] = 1;
        if (leaving) {
            state.shots.in_flight[i] = 0;
        } else if (ends_a_flight(state, i)) {
            ++state.slow_contacts_per_component[c];
        }
        sustain_contact(state, i, c, contact, v1, p1, dt);
        return false;
    }
    // Sustained contact acts at the step end, on the contact found there.
    const Contact at_step_end = contact;

    const double u = *touch, back = dt - u;
    Vec3 v_touch = v1 - g * back;
    Vec3 centre_touch = p1 - v1 * back + 0.5 * g * back * back;
    if (!parabola_) {
        // The state at the touch from the flight model itself, flown back from the step end (the
        // arc above found the touch time; taken with it, the speed was off by 6e-7 of itself).
        centre_touch = p1;
        v_touch = v1;
        shot_size(*model_, s, i).flight->advance(centre_touch, v_touch, -back);
    }
    Vec3 x_touch = centre_touch - R * n;
    if (turning_gap) {
        // The part has turned since the touch: the feature touched, its normal and the contact
        // point are those of the part in its pose at the touch time, not at the step end.
        const MovingMeshGap::Touch at = turning_gap->touch_at(u);
        contact.normal = at.normal;
        contact.mesh_triangle = at.mesh_triangle;
        const auto tt = static_cast<std::size_t>(at.mesh_triangle);
        contact.triangle = comp.mesh->source_facet.empty() ? at.mesh_triangle : comp.mesh->source_facet[tt];
        x_touch = at.point;
    }
    const Vec3 v_surface = kin.point_velocity(x_touch, t0_, u);
    const double approach = -(v_touch - v_surface).dot(n);
    const contact::SurfaceLaw& law = *comp.law;

    touched_[i] = 1;
    if (vibrating && leaving && !(u > u_lo)) {
        // The shot rides the plate from the touch just taken (the plate presses it): the ride goes
        // on to the step end, where sustained contact acts (launches within the step are taken
        // where the ride starts, see below).
        if (at_step_end.gap >= 0.0) return false;
        state.shots.in_flight[i] = 0;
        sustain_contact(state, i, c, at_step_end, v1, p1, dt);
        return false;
    }
    const bool impact = contact::is_impact(approach, model_->impact_speed_m_per_s);
    if (impact || vibrating) {
        // On the vibrating plate a slower touch is followed too, unlogged, as the event-driven scheme
        // does: the plate that touched the shot may press it along (a ride) or come back within the
        // step. Stopping such a shot at the step end let the plate pass through it in between when
        // the step ended with the two apart.
        const Pose pose_touch = kin.pose(t0_, u);
        const ContactSite site{
            static_cast<int>(i), static_cast<int>(c), contact.mesh_triangle, &pose_touch, x_touch, t0_.hi + (t0_.lo + u), 0.0};
        contact::SurfaceContactResponse r = law.impact(surface_input(*model_, state.shots, site, v_touch, v_surface, n, impact, 0.0, 0.0,
                                                                     instant_contact_state(contact_scratch_, *model_, c)),
                                                       law_state(state, c));
        bool rides = false;
        double closing_accel = 0.0;  // m/s2
        if (vibrating) {
            // Riding the plate: while the plate accelerates into the shot faster than gravity, a slow
            // rebound is caught again within microseconds, then again, ever slower (a Zeno sequence).
            // Each rebound is followed, pass after pass, until one is slower than the ride speed: the
            // shot then leaves with the plate and rides it until the plate decelerates faster than
            // gravity, as the real shot does (the contact policy both schemes follow).
            closing_accel = kin.point_acceleration(x_touch, t0_, u).dot(n) - g.dot(n);
            if (contact::rebound_rides(closing_accel, r.vn_out)) {
                r.v_shot -= r.vn_out * n;
                r.vn_out = 0.0;
                rides = true;
            }
        }
        if (impact) {
            // A rebound starts a free flight; a ride stays in contact with the plate.
            state.shots.in_flight[i] = rides ? 0 : 1;
        } else if (ends_a_flight(state, i)) {
            ++state.slow_contacts_per_component[c];
        }
        const Vec3 dv = r.v_shot - v_touch;
        if (parabola_) {
            s.set_velocity(i, v1 + dv);
            s.set_position(i, p1 + dv * back);
        } else {
            fly(s, i, centre_touch, r.v_shot, back);  // drag acts on the rebound's own velocity
        }
        last_touch_[i] = u;
        last_touch_component_[i] = static_cast<int>(c);
        forget_clearances(i);
        if (impact)
            record_impact(*model_, state, impacts, t0_.hi + (t0_.lo + u), static_cast<int>(i), static_cast<int>(c), contact.triangle,
                          pose_touch, x_touch, v_touch, v_surface, r);
        if (rides) {
            ++stats_.rides;
            if (!launch_within_step(state, i, c, n, centre_touch, r.v_shot, u, pose_touch, dt)) {
                // Riding on to the step end: sustained contact acts there, on the step-end contact
                // plane moved by the ride's change of course. (Searching again from the touch would
                // find the plate a rounding later, ride again, and so on, pass after pass.)
                Contact riding = at_step_end;
                riding.gap += riding.normal.dot(dv * back);
                if (riding.gap < 0.0) {
                    state.shots.in_flight[i] = 0;
                    sustain_contact(state, i, c, riding, v1 + dv, p1 + dv * back, dt);
                }
                return false;
            }
        }
        return true;
    }
    // Slower than the impact speed: sustained contact, not an impact (contact_law.h).
    if (at_step_end.gap >= 0.0) return false;  // a slow touch that has already ended
    if (ends_a_flight(state, i)) ++state.slow_contacts_per_component[c];
    sustain_contact(state, i, c, at_step_end, v1, p1, dt);
    return false;
}

bool TimeStepping::launch_within_step(SimulationState& state, std::size_t i, std::size_t c, const Vec3& n, const Vec3& centre,
                                      const Vec3& v_after, double u, const Pose& pose_touch, double dt) {
    // The plate's acceleration along n is -A w^2 k sin(phase) (k = a.n); it presses the shot while
    // that exceeds g.n, i.e. until sin(phase) rises through eps = -g.n / (A w^2 k): the launch, as
    // in the event-driven scheme (which rides exactly). Launched before the step end, the shot
    // leaves with the plate's velocity then, its slip along the plate reduced by Coulomb friction,
    // and flies to the step end; otherwise it rides on and sustained contact acts at the step end.
    const Component& comp = model_->components[c];
    const Kinematics& kin = comp.kinematics;
    const Vec3 g = model_->gravity_m_per_s2;
    const double w = kin.angular_frequency();
    const double w2a = kin.amplitude_m * w * w * kin.axis.dot(n);
    if (!(w2a > 0.0)) return false;
    const double phase = 2.0 * M_PI * t0_.cycle_fraction(kin.frequency_hz, u) + kin.phase_rad;
    // Infinite when the plate never pulls away faster than gravity: it holds the shot.
    const double u_release = u + seconds_to_release(phase, -g.dot(n) / w2a, w);
    // The flight is started kReleaseDelayPeriods after the release, as the event scheme does.
    if (!(u_release + kReleaseDelayPeriods / kin.frequency_hz < dt)) return false;
    const double ride = u_release - u;
    const Vec3 plate_v0 = kin.axis * kin.displacement_rate(t0_, u);
    const Vec3 plate_v1 = kin.axis * kin.displacement_rate(t0_, u_release);
    const Vec3 rel = v_after - plate_v0;
    const Vec3 slip = rel - rel.dot(n) * n;
    // The normal impulse per unit mass is what the plate gave the shot beyond gravity.
    const double impulse = std::max(0.0, (plate_v1 - plate_v0).dot(n) - g.dot(n) * ride);
    // Friction over the ride through the pair's law: its sustained contact with the plate pressing
    // the shot by impulse / ride on average over the ride.
    const ContactSite site{static_cast<int>(i),
                           static_cast<int>(c),
                           -1,
                           &pose_touch,
                           centre - shot_radius(*model_, state.shots, i) * n,
                           t0_.hi + (t0_.lo + u),
                           0.0};
    const contact::SurfaceContactResponse r =
        comp.law->sustain(surface_input(*model_, state.shots, site, plate_v0 + slip, plate_v0, n, false, ride > 0.0 ? impulse / ride : 0.0,
                                        ride, instant_contact_state(contact_scratch_, *model_, c)),
                          law_state(state, c));
    const Vec3 kept = r.v_shot - plate_v0 - (r.v_shot - plate_v0).dot(n) * n;
    const Vec3 c_release = centre + kin.axis * (kin.displacement(t0_, u_release) - kin.displacement(t0_, u)) + slip * ride;
    const Vec3 v_launch = plate_v1 + kept;
    const double fly_s = dt - u_release;
    ShotArrays& s = state.shots;
    if (parabola_) {
        const FlightState at_step_end = after_release({c_release, v_launch}, g, fly_s);
        s.set_velocity(i, at_step_end.velocity_m_per_s);
        s.set_position(i, at_step_end.position_m);
    } else {
        fly(s, i, c_release, v_launch, fly_s);
    }
    s.in_flight[i] = 1;
    last_touch_[i] = u_release + kReleaseDelayPeriods / kin.frequency_hz;
    return true;
}

bool TimeStepping::collected(SimulationState& state, std::size_t i) const {
    // Looked at the step's end: a shot whose centre entered a sink within the step is collected
    // there (unlike the event-driven scheme, not at the exact moment it entered).
    const Vec3 p = state.shots.position(i);
    for (std::size_t k = 0; k < model_->sinks.size(); ++k)
        if (model_->sinks[k]->contains(p)) {
            state.shots.active[i] = 0;
            ++state.collected_per_sink[k];
            return true;
        }
    return false;
}

bool TimeStepping::ends_a_flight(SimulationState& state, std::size_t i) {
    // Counting rule: a slow contact is a free flight ending in sustained contact. A shot lying
    // still, rolling or sliding is in sustained contact at every step; it is counted only when it
    // got there from a flight (in_flight set by an impact's rebound or by a whole step touching
    // nothing), so a resting shot counts once, however long it rests.
    const bool was_flying = state.shots.in_flight[i] != 0;
    state.shots.in_flight[i] = 0;
    return was_flying;
}

void TimeStepping::note_free_flights(SimulationState& state) {
    unsigned char* in_flight = state.shots.in_flight.data();
    for (std::size_t i = 0; i < touched_.size(); ++i) in_flight[i] |= static_cast<unsigned char>(!touched_[i]);
}

void TimeStepping::sustain_contact(SimulationState& state, std::size_t i, std::size_t c, const Contact& contact, const Vec3& v1,
                                   const Vec3& p1, double dt) {
    // Sustained contact (resting, rolling, sliding, riding) at the step end: the approach stops,
    // friction acts, and the overlap is removed by moving the shot out along the normal (no energy added).
    const Component& comp = model_->components[c];
    const Kinematics& kin = comp.kinematics;
    const Vec3& n = contact.normal;
    const Vec3 g = model_->gravity_m_per_s2;
    const Vec3 v_surface_end = kin.point_velocity(contact.point, t0_, dt);
    const double pressing = std::max(0.0, -g.dot(n) + kin.point_acceleration(contact.point, t0_, dt).dot(n));
    const ContactSite site{static_cast<int>(i), static_cast<int>(c),    contact.mesh_triangle,      &pose_end_[c],
                           contact.point,       t0_.hi + (t0_.lo + dt), std::max(0.0, -contact.gap)};
    const contact::SurfaceContactResponse r =
        comp.law->sustain(surface_input(*model_, state.shots, site, v1, v_surface_end, n, false, pressing, dt,
                                        sustained_contact_state(state, *model_, static_cast<int>(i), c, stamp_)),
                          law_state(state, c));
    ShotArrays& s = state.shots;
    s.set_velocity(i, r.v_shot);
    s.set_position(i, p1 - contact.gap * n);
    if (-contact.gap > contact::kOverlapWorthCounting * shot_radius(*model_, s, i)) ++state.health.mesh_overlap_corrections;
}

void TimeStepping::check_health(SimulationState& state) {
    StageTimer timer(stats_, Stage::health);
    ShotArrays& s = state.shots;
    const Vec3 lo = model_->world_lo, hi = model_->world_hi;
    double fastest2 = 0.0;
    const double t = t0_.seconds();
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (!s.active[i]) continue;
        const double v2 = s.vx[i] * s.vx[i] + s.vy[i] * s.vy[i] + s.vz[i] * s.vz[i];
        const double x = s.x[i], y = s.y[i], z = s.z[i];
        if (!std::isfinite(v2) || !std::isfinite(x + y + z)) {
            s.active[i] = 0;
            ++state.health.non_finite;
            continue;
        }
        if (collected(state, i)) continue;
        if (x < lo.x() || y < lo.y() || z < lo.z() || x > hi.x() || y > hi.y() || z > hi.z()) {
            s.active[i] = 0;
            ++state.health.shot_lost;
            state.lost.push_back({static_cast<int>(i), t, Vec3(x, y, z)});
            continue;
        }
        fastest2 = std::max(fastest2, v2);
    }
    state.fastest_shot_m_per_s = std::sqrt(fastest2);
}

}  // namespace peensim
