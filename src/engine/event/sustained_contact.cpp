#include "engine/event/sustained_contact.h"

#include <algorithm>
#include <cmath>

#include "collision/surface_clearance.h"
#include "contact/contact_policy.h"
#include "engine/event/shot_motion.h"
#include "engine/impact_recording.h"
#include "engine/law_input.h"

namespace peensim {

namespace {
// of R: a shot in sustained contact this close to a surface stays on it. Rolling over a curved
// surface opens a gap of (v dt)^2 / 2r per substep (6e-5 R for a 1 mm shot at 0.5 m/s on a 5 mm
// radius); flying off it between substeps would leave a gap of a few nm to close by conservative
// advancement, whose steps (gap / speed) crawl there.
constexpr double kSustainSlack = 1e-3;
}  // namespace

SustainedContact::SustainedContact(std::shared_ptr<const Model> model, double resting_speed_m_per_s)
    : model_(std::move(model)),
      g_(model_->gravity_m_per_s2),
      resting_speed_(resting_speed_m_per_s),
      contact_state_(uses_contact_state(*model_)) {
    neighbours_.reserve(64);
}

SustainedContact::Next SustainedContact::end_of_substep(int i, double t, Vec3 p, Vec3 v, const SimTime& epoch, std::span<EventShot> shots,
                                                        const std::vector<unsigned char>& active, const PairPredictor& pairs,
                                                        const WallPredictor& walls, SimulationState& state,
                                                        std::vector<ImpactRecord>& impacts) {
    EventShot& s = shots[static_cast<std::size_t>(i)];
    const Model& m = *model_;
    // The contacts a law remembers: those not found again at this substep's end have ended.
    const std::uint64_t stamp = contact_state_ ? state.contacts.begin_resolution() : 0;
    const double now_s = epoch.hi + (epoch.lo + t);  // absolute
    const double R = s.radius_m;                     // m, this shot's
    const double slack = kContactSlack * R;
    bool touching = false, moving_support = false;
    Vec3 support = Vec3::Zero();  // the contact normal gravity presses on most
    const auto consider_support = [&](const Vec3& n) {
        if (g_.dot(n) < g_.dot(support)) support = n;
    };
    // Shot it rests on or leans against: held like a wall (only this shot's motion changes). Shot
    // first, surfaces last, so that a push from a neighbour never leaves the shot inside a surface.
    const double reach = R + m.max_shot_radius_m + slack;  // the farthest a touching neighbour's centre can be
    pairs.overlapping(p - Vec3::Constant(reach), p + Vec3::Constant(reach), neighbours_);
    for (const int j : neighbours_) {
        if (j == i || !active[static_cast<std::size_t>(j)]) continue;
        const EventShot& o = shots[static_cast<std::size_t>(j)];
        const Vec3 pj = motion_position(o, walls, t);
        const Vec3 d = p - pj;
        const double dist = d.norm();
        const double touch = R + o.radius_m;  // m, centre distance at contact
        if (!(dist < touch + slack) || !(dist > 0.0)) continue;
        touching = true;
        const Vec3 n = d / dist;
        consider_support(n);
        // Held like a wall: the shot-shot law in sustained contact against a held partner takes the
        // approach away from this shot alone (the law's normal points from this shot to j).
        const Vec3 vj = motion_velocity(o, walls, t);
        contact::ShotShotInput held = shot_shot_input(m, state.shots, i, j, v, vj, -n, contact::ShotShotMode::sustained, dist, now_s);
        held.j_held = true;
        v = m.shot_shot_law->respond(held).v_i;
        if (dist < touch) {
            // At most a tenth of R per substep: a jammed pile relaxes over a few substeps instead of
            // pushing a shot through a wall at once.
            p += std::min(touch - dist, 0.1 * R) * n;
            if (touch - dist > contact::kOverlapWorthCounting * R) ++state.health.shot_overlap_corrections;
        }
        // A neighbour still moving (not asleep, not as still as this shot must be) keeps it awake.
        if (o.motion == EventMotion::flying || o.motion == EventMotion::riding || o.motion == EventMotion::pooled ||
            vj.norm() >= resting_speed_)
            moving_support = true;
    }
    for (std::size_t c = 0; c < m.components.size(); ++c) {
        const Component& comp = m.components[c];
        const Pose pose = comp.kinematics.pose(epoch, t);
        const Vec3 local = pose.to_component(p);
        MeshCollider::Closest closest;
        MeshCollider::QueryCounters counters;
        if (!comp.collider->closest_within(local, R * (1.0 + kSustainSlack), closest, counters)) continue;
        if (!(closest.distance > 0.0)) continue;
        const SurfaceClearance clear = surface_clearance(*comp.mesh, comp.solid, local, closest);
        const double gap = clear.distance_m - R;
        if (gap < -contact::kDeepPenetration * R) ++state.health.deep_penetrations;
        touching = true;
        const Vec3 n = pose.rotation * clear.normal;
        const Vec3 point = pose.to_world(closest.point);
        const Vec3 vs = comp.kinematics.point_velocity(point, epoch, t);
        moving_support |= comp.kinematics.moves();
        const double approach = -(v - vs).dot(n);
        consider_support(n);
        const ContactSite site{i, static_cast<int>(c), closest.triangle, &pose, point, now_s, std::max(0.0, -gap)};
        if (approach > resting_speed_) {
            // Slid or rolled into another surface fast enough to bounce: a rebound at the substep's
            // end, an impact if at least the impact speed.
            const bool impact = contact::is_impact(approach, m.impact_speed_m_per_s);
            if (!impact && s.in_flight) ++state.slow_contacts_per_component[c];
            s.in_flight = impact;
            const contact::SurfaceContactResponse r =
                comp.law->impact(surface_input(m, state.shots, site, v, vs, n, impact, 0.0, 0.0, instant_contact_state(scratch_, m, c)),
                                 law_state(state, c));
            if (impact)
                record_impact(m, state, impacts, now_s, i, static_cast<int>(c), walls.source_facet(c, closest.triangle), pose, point, v, vs,
                              r);
            v = r.v_shot;
        } else {
            const double pressing = std::max(0.0, -g_.dot(n) + comp.kinematics.point_acceleration(point, epoch, t).dot(n));
            v = comp.law
                    ->sustain(surface_input(m, state.shots, site, v, vs, n, false, pressing, s.substep_s,
                                            sustained_contact_state(state, m, i, c, stamp)),
                              law_state(state, c))
                    .v_shot;
        }
        if (gap < 0.0) {
            p -= gap * n;
            if (-gap > contact::kOverlapWorthCounting * R) ++state.health.mesh_overlap_corrections;
        }
    }
    if (contact_state_) state.contacts.end_unseen(stamp, i);
    if (!touching) {
        s.in_flight = true;
        return {p, v, Vec3::Zero(), EventMotion::flying};
    }
    s.quiet_substeps = (!moving_support && v.norm() < resting_speed_) ? s.quiet_substeps + 1 : 0;
    if (s.quiet_substeps >= kQuietSubsteps) return {p, Vec3::Zero(), Vec3::Zero(), EventMotion::sleeping};
    return {p, v - std::min(0.0, v.dot(support)) * support, support, EventMotion::sustained};
}

}  // namespace peensim
