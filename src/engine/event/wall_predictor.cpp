#include "engine/event/wall_predictor.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "collision/surface_clearance.h"
#include "common/float_limits.h"
#include "engine/event/turning_frame_path.h"
#include "kernels/box_entry.h"
#include "kernels/closest_point.h"
#include "kernels/swept_sphere_box.h"
#include "kernels/vibrating_plane_toi.h"

namespace peensim {

namespace {
constexpr int kMaxAdvancement = 2000;  // conservative-advancement iterations per search (then it resumes later)
constexpr double kSkimBand = 1e-6;     // gap (x R) within which a gap that stops closing is a touch
constexpr double kCrawlRatio = 0.8;    // a step that leaves more of the gap than this crawls: a turning part is then swept
}  // namespace

WallPredictor::WallPredictor(std::shared_ptr<const Model> model) : model_(std::move(model)) {
    const Model& m = *model_;
    face_of_.assign(m.components.size(), -1);
    for (std::size_t k = 0; k < m.components.size(); ++k) {
        const Component& c = m.components[k];
        if (c.role != ComponentRole::sonotrode || c.kinematics.kind != Kinematics::Kind::vibrating || !c.kinematics.moves()) continue;
        face_of_[k] = static_cast<int>(faces_.size());
        faces_.push_back(build_sonotrode_face(c, face_direction(m, k)));
        face_phase_at_zero_.push_back(faces_.back().plane.phase_rad);
    }
    for (const Component& c : m.components) {
        std::vector<int> facets(c.mesh->triangle_count());
        for (std::size_t t = 0; t < facets.size(); ++t)
            facets[t] = c.mesh->source_facet.empty() ? static_cast<int>(t) : c.mesh->source_facet[t];
        facets_.push_back(std::move(facets));
        surface_speed_.push_back(c.kinematics.peak_surface_speed(c.max_axis_distance_m));
        if (c.role != ComponentRole::sonotrode) moving_part_speed_ = std::max(moving_part_speed_, surface_speed_.back());
    }
}

void WallPredictor::set_epoch(const SimTime& epoch) {
    epoch_ = epoch;
    for (std::size_t f = 0; f < faces_.size(); ++f)
        faces_[f].plane.phase_rad = face_phase_at_zero_[f] + 2.0 * M_PI * epoch_.cycle_fraction(faces_[f].plane.frequency_hz);
}

Vec3 WallPredictor::face_direction(const Model& m, std::size_t c) {
    // Along the vibration axis, against gravity: the face shot fall onto, ride and are thrown
    // from. Its other faces (a sonotrode in the lid faces down) are moving meshes like any other,
    // exact by conservative advancement.
    const Vec3 up = m.gravity_m_per_s2.norm() > 0.0 ? Vec3(-m.gravity_m_per_s2.normalized()) : Vec3::UnitZ();
    const Vec3& axis = m.components[c].kinematics.axis;
    return axis.dot(up) >= 0.0 ? axis : Vec3(-axis);
}

WallEvent WallPredictor::first_event(const Trajectory& path, double R, double t, double t_search, double window_end,
                                     StepStats& stats) const {
    WallEvent w;
    const double t_leave = leave_time(path, t);
    w.time = std::min(t_leave, window_end);
    w.kind = t_leave <= window_end ? WallKind::leave : WallKind::none;
    const Model& m = *model_;
    // A sink entered no later than anything else is where the flight ends (collected, not lost).
    for (std::size_t k = 0; k < m.sinks.size(); ++k) {
        const std::optional<double> in = m.sinks[k]->first_entry(path, t, w.time);
        if (in && *in <= w.time) {
            w.time = *in;
            w.kind = WallKind::sink;
            w.component = static_cast<int>(k);
        }
    }
    // The window's sphere bounds: a component whose (swept) bounds they miss cannot be reached.
    Vec3 reach_lo, reach_hi;
    path.bounds(t, w.time, reach_lo, reach_hi);
    reach_lo -= Vec3::Constant(1.001 * R);
    reach_hi += Vec3::Constant(1.001 * R);
    for (std::size_t k = 0; k < m.components.size(); ++k) {
        const int c = static_cast<int>(k);
        const Component& comp = m.components[k];
        if ((reach_hi.array() < comp.world_lo.array()).any() || (reach_lo.array() > comp.world_hi.array()).any()) continue;
        ++stats.mesh_predictions;
        WallEvent found;
        bool hit = false;
        if (face_of_[k] >= 0) {
            const SonotrodeFace& face = faces_[static_cast<std::size_t>(face_of_[k])];
            hit = face_contact(c, path, R, t_search, w.time, found, stats);
            if (face.rest_collider && !(hit && found.overlapping)) {
                // The sonotrode's other triangles move by at most A: a static sweep with the radius
                // grown by A finds when the shot can first reach them, advancement settles it.
                MeshCollider::Hit near;
                MeshCollider::SweepCounters counters;
                const Pose& rest = comp.kinematics.rest;
                const Trajectory local{rest.to_component(path.p0), rest.rotation.transpose() * path.v0, rest.rotation.transpose() * path.g,
                                       t};
                const double t_limit = hit ? found.time : w.time;
                const ToiStatus st =
                    face.rest_collider->first_hit(local, R + comp.kinematics.amplitude_m, t_search, t_limit, near, counters);
                if (st != ToiStatus::miss) {
                    WallEvent side;
                    const AdvancementResult r = advance_to_contact(c, *face.rest_collider, face.rest_mesh->source_facet, surface_speed_[k],
                                                                   path, R, near.contact.time, t_limit, side);
                    if (r.exhausted) resume_search_at(w, r.searched_until, c, stats);
                    if (r.found && (!hit || side.time < found.time || side.overlapping)) found = side, hit = true;
                }
            }
        } else if (comp.kinematics.moves()) {
            SweptSphere sweep(path, R, t_search, w.time);
            TimeSpan span;
            if (sweep.span(comp.world_lo, comp.world_hi, span)) {
                const AdvancementResult r = advance_to_contact(c, *comp.collider, facets_[k], surface_speed_[k], path, R,
                                                               std::max(t_search, span.first), std::min(w.time, span.last), found);
                if (r.exhausted) resume_search_at(w, r.searched_until, c, stats);
                hit = r.found;
            }
        } else {
            hit = static_contact(c, path, R, t_search, w.time, found, stats);
        }
        if (!hit) continue;
        if (found.overlapping || found.time < w.time) {
            w = found;
            w.kind = WallKind::contact;
            w.component = c;
            if (found.overlapping) break;  // nothing can come first
        }
    }
    return w;
}

double WallPredictor::leave_time(const Trajectory& path, double t) const {
    return first_time_outside_box(path, model_->world_lo, model_->world_hi, t, kInf).value_or(kInf);
}

void WallPredictor::resume_search_at(WallEvent& w, double t, int component, StepStats& stats) {
    ++stats.search_resumes;
    if (!(t < w.time)) return;
    w = WallEvent{};
    w.time = t;
    w.kind = WallKind::none;
    w.component = component;
    w.resumed = true;
}

bool WallPredictor::put_out_of_solid(std::size_t c, double R, double t, WallEvent& w, Vec3& p) const {
    const Component& comp = model_->components[c];
    const Pose pose = comp.kinematics.pose(epoch_, t);
    const auto tri = static_cast<std::size_t>(w.mesh_triangle);
    const Vec3& a = comp.mesh->corner(tri, 0);
    const Vec3& b = comp.mesh->corner(tri, 1);
    const Vec3& e = comp.mesh->corner(tri, 2);
    const Vec3 local = pose.to_component(p);
    const ClosestPoint foot = closest_point_on_triangle(local, a, b, e);
    const Vec3 face = (b - a).cross(e - a);
    // Behind the face itself (at an edge or a vertex the side of one face does not decide).
    if (foot.feature != TriangleFeature::face || !(face.dot(local - foot.point) < 0.0)) return false;
    w.normal = pose.rotation * face.normalized();
    w.point = pose.to_world(foot.point);
    p = w.point + R * w.normal;
    if (comp.kinematics.moves()) {
        w.surface_velocity = comp.kinematics.point_velocity(w.point, epoch_, t);
        w.surface_acceleration = comp.kinematics.point_acceleration(w.point, epoch_, t);
    }
    return true;
}

bool WallPredictor::static_contact(int c, const Trajectory& path, double R, double t, double t_end, WallEvent& out,
                                   StepStats& stats) const {
    const Component& comp = model_->components[static_cast<std::size_t>(c)];
    const Pose& rest = comp.kinematics.rest;
    const Mat3 to_local = rest.rotation.transpose();
    const Trajectory local{rest.to_component(path.p0), to_local * path.v0, to_local * path.g, path.t0};
    MeshCollider::Hit hit;
    MeshCollider::SweepCounters counters;
    const ToiStatus st = comp.collider->first_hit(local, R, t, t_end, hit, counters);
    stats.bvh_queries += 1;
    stats.triangle_tests += counters.leaves_visited;
    stats.bvh_sweeps_gated += counters.windows_gated;
    if (st == ToiStatus::miss) return false;
    out.time = st == ToiStatus::overlapping ? t : hit.contact.time;
    out.point = rest.to_world(hit.contact.point);
    out.normal = rest.rotation * hit.contact.normal;
    out.triangle = facets_[static_cast<std::size_t>(c)][static_cast<std::size_t>(hit.triangle)];
    out.mesh_triangle = hit.triangle;
    out.overlapping = st == ToiStatus::overlapping;
    if (out.overlapping) out.depth = std::max(0.0, R - (path.position(t) - out.point).norm());
    return true;
}

bool WallPredictor::face_contact(int c, const Trajectory& path, double R, double t, double t_end, WallEvent& out, StepStats& stats) const {
    const SonotrodeFace& face = faces_[static_cast<std::size_t>(face_of_[static_cast<std::size_t>(c)])];
    PlaneContact pc;
    const ToiStatus st = vibrating_plane_toi(path, R, face.plane, t, t_end, pc);
    ++stats.touch_searches;
    if (st == ToiStatus::miss) return false;
    // Only where the plane is the face: the foot of the centre must lie on one of its triangles.
    const Component& sono = model_->components[static_cast<std::size_t>(c)];
    const Pose pose = sono.kinematics.pose(epoch_, pc.time);
    int triangle = -1;
    if (!face.contains(sono, pose.to_component(pc.point), kTouchDistance * R + 1e-12, triangle)) return false;
    out.time = pc.time;
    out.point = pc.point;
    out.normal = pc.normal;
    out.surface_velocity = pc.plate_velocity;
    out.surface_acceleration = pc.plate_acceleration;
    out.face = true;
    out.triangle = facets_[static_cast<std::size_t>(c)][static_cast<std::size_t>(triangle)];
    out.overlapping = st == ToiStatus::overlapping;
    if (out.overlapping) out.depth = std::max(0.0, -vibrating_plane_gap(path, R, face.plane, t));
    return true;
}

WallPredictor::AdvancementResult WallPredictor::advance_to_contact(int c, const MeshCollider& collider, const std::vector<int>& facets,
                                                                   double surface_speed, const Trajectory& path, double R, double t,
                                                                   double t_end, WallEvent& out) const {
    // Conservative advancement: the distance from the centre to the moving mesh changes no faster
    // than the shot's speed plus the fastest surface point's, so after measuring a gap d the shot
    // cannot touch for d / (that speed). Converges on the touch from outside; exact distances
    // come from the BVH in the component's frame at its pose at each time.
    const Component& comp = model_->components[static_cast<std::size_t>(c)];
    const Kinematics& kin = comp.kinematics;
    const bool solid = comp.solid && &collider == comp.collider.get();
    const double V = path.max_speed(t, t_end) + surface_speed;
    if (!(V > 0.0)) return {};
    const double look = 2.0 * R, tolerance = kTouchDistance * R, skim = kSkimBand * R;
    double u = t;
    double last_gap = kInf;  // m: the gap the previous step measured
    bool at_start = true;
    for (int it = 0; it < kMaxAdvancement; ++it) {
        if (u > t_end) return {};
        const Pose pose = kin.pose(epoch_, u);
        const Vec3 centre = path.position(u);
        const Vec3 local = pose.to_component(centre);
        MeshCollider::Closest closest;
        MeshCollider::QueryCounters counters;
        if (!collider.closest_within(local, R + look, closest, counters)) {
            u += look / V;
            at_start = false;
            continue;
        }
        const SurfaceClearance clear = surface_clearance(solid ? *comp.mesh : collider_mesh(c, collider), solid, local, closest);
        const double d = clear.distance_m - R;
        // Skimming: a gap within the skim band that the last step left about as it was (a shot
        // moving along the surface at a hair's distance, as a graze leaves it). Conservative advancement
        // would step gap / V for ever (a rotating gear's run stalled so, at a gap of 1e-9 R); it
        // is a touch.
        const bool skimming = d <= skim && std::abs(d - last_gap) <= 0.5 * std::max(d, last_gap);
        const bool crawling = d > kCrawlRatio * last_gap;
        last_gap = d;
        if (d > tolerance && !skimming) {
            // A crawl (the shot flies along the surface, or at it at a shallow angle: tens of steps to
            // cross a few radii) on a turning part jumps as far as a sweep in the part's frame, grown
            // by at most half the gap, allows; it closes on a touch cubically. Where the plain steps
            // close in fast, they are the cheaper (a distance query against a sweep).
            u = crawling ? std::max(u + d / V, clear_until(comp, collider, path, R, u, t_end, 0.5 * d)) : u + d / V;
            at_start = false;
            continue;
        }
        out.point = pose.to_world(closest.point);
        out.normal = pose.rotation * clear.normal;
        out.surface_velocity = kin.point_velocity(out.point, epoch_, u);
        out.surface_acceleration = kin.point_acceleration(out.point, epoch_, u);
        out.overlapping = d < -tolerance;
        const double approach = -(path.velocity(u) - out.surface_velocity).dot(out.normal);
        if (!out.overlapping && approach <= 0.0 && !(skimming && !at_start)) {
            // Touching but separating (the shot has just left this surface): not a contact; move on
            // by a hair so that time progresses, and keep watching for the return.
            u += (at_start ? 1e-3 : 1e-6) * R / V;
            at_start = false;
            continue;
        }
        // Skimming without approach is a graze: the engine slides the shot on, or holds it in
        // sustained contact when grazes follow each other (EventStepping::touch). Stepping past it
        // a hair at a time would take millions of searches to cross a face.
        out.time = u;
        out.depth = std::max(0.0, -d);
        out.triangle = facets[static_cast<std::size_t>(closest.triangle)];
        out.mesh_triangle = closest.triangle;
        return {true, false, u};
    }
    // Out of iterations (a shot skimming a moving surface): nothing was found up to u, and the search
    // resumes from there (an event), so no contact after u can be missed.
    return {false, true, u};
}

double WallPredictor::clear_until(const Component& comp, const MeshCollider& collider, const Trajectory& path, double R, double u,
                                  double t_end, double allowance) const {
    // A turning part: its parabola in the part's frame, swept with the radius grown by how far the
    // centre can stray from it (at most `allowance`), over the stretch where it stays within that.
    // The sweep's first touch can only be early; a miss clears the stretch.
    if (comp.kinematics.kind != Kinematics::Kind::rotating || !(allowance > 0.0) || !(t_end > u)) return u;
    const TurningFramePath local = turning_frame_path(comp.kinematics, epoch_, path, u, t_end);
    double stretch = local.stretch_within(allowance);
    const bool to_end = !(stretch < t_end - u);
    if (to_end) stretch = t_end - u;
    MeshCollider::Hit hit;
    MeshCollider::SweepCounters counters;
    switch (collider.first_hit(local.parabola, R + local.deviation(stretch), u, u + stretch, hit, counters)) {
        case ToiStatus::miss: return to_end ? std::nextafter(t_end, kInf) : u + stretch;
        case ToiStatus::impact: return hit.contact.time;
        case ToiStatus::overlapping: break;
    }
    return u;
}

const TriangleMesh& WallPredictor::collider_mesh(int c, const MeshCollider& collider) const {
    const Component& comp = model_->components[static_cast<std::size_t>(c)];
    return &collider == comp.collider.get() ? *comp.mesh
                                            : *faces_[static_cast<std::size_t>(face_of_[static_cast<std::size_t>(c)])].rest_mesh;
}

}  // namespace peensim
