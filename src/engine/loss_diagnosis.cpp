#include "engine/loss_diagnosis.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "collision/mesh_collider.h"

namespace peensim {

namespace {

constexpr double kHair = 1e-6;       // of R: the swept sphere is this much smaller (the start touches a surface)
constexpr double kStartSkip = 1e-9;  // s, the sweep starts this long after the last event (which touched a surface)

// The first time in [t_from, t_to] the swept sphere overlaps component c, verified at the
// component's pose at that very time (a moving component is swept at its pose at t_to first):
// returns false if it never does.
bool first_overlap(const Model& model, std::size_t c, const SimTime& epoch, const Trajectory& path, double radius, double t_from,
                   double t_to, double& when, Vec3& where) {
    const Component& comp = model.components[c];
    const Kinematics& kin = comp.kinematics;
    const Pose pose = kin.pose(epoch, t_to);
    const Mat3 to_local = pose.rotation.transpose();
    const Trajectory local{pose.to_component(path.p0), to_local * path.v0, to_local * path.g, path.t0};
    MeshCollider::Hit hit;
    MeshCollider::SweepCounters counters;
    if (comp.collider->first_hit(local, radius, t_from, t_to, hit, counters) == ToiStatus::miss) return false;
    when = std::max(t_from, hit.contact.time);
    if (kin.moves()) {
        const Pose then = kin.pose(epoch, when);
        MeshCollider::Closest closest;
        MeshCollider::QueryCounters qc;
        if (!comp.collider->closest_within(then.to_component(path.position(when)), radius, closest, qc)) return false;
        where = then.to_world(closest.point);
        return true;
    }
    where = pose.to_world(hit.contact.point);
    return true;
}

}  // namespace

void diagnose_loss(const Model& model, const SimTime& epoch, const Trajectory& path, double R, double t_from, double t_to, LostShot& lost) {
    const double begin = std::min(t_to, t_from + kStartSkip);
    lost.from_time_s = epoch.hi + (epoch.lo + t_from);
    lost.from_m = path.position(t_from);
    double earliest = std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < model.components.size(); ++c) {
        const Component& comp = model.components[c];
        // A vibrating sonotrode is swept at one pose: shrink the sphere by its amplitude so that a
        // flight that cleared it at the time cannot be taken for a crossing.
        const double radius = R * (1.0 - kHair) - (comp.kinematics.kind == Kinematics::Kind::vibrating ? comp.kinematics.amplitude_m : 0.0);
        if (!(radius > 0.0)) continue;
        double when = 0.0;
        Vec3 where;
        if (first_overlap(model, c, epoch, path, radius, begin, t_to, when, where) && when < earliest) {
            earliest = when;
            lost.cause = LossCause::engine_error;
            lost.component = static_cast<int>(c);
            lost.where_m = where;
        }
    }
    if (lost.cause == LossCause::engine_error) return;
    // A leak: where the centre left the chamber components' bounds (bisection on the flight).
    lost.cause = LossCause::leak;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Component& comp : model.components)
        if (comp.role == ComponentRole::chamber || comp.role == ComponentRole::sonotrode)
            lo = lo.cwiseMin(comp.world_lo), hi = hi.cwiseMax(comp.world_hi);
    const auto inside = [&](double t) {
        const Vec3 p = path.position(t);
        return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
    };
    double a = t_from, b = t_to;
    if (inside(a) && !inside(b))
        for (int k = 0; k < 100 && b - a > 1e-15; ++k) (inside(0.5 * (a + b)) ? a : b) = 0.5 * (a + b);
    lost.where_m = path.position(a);
    double clearance = std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < model.components.size(); ++c) {
        const Component& comp = model.components[c];
        const Pose pose = comp.kinematics.pose(epoch, a);
        MeshCollider::Closest closest;
        MeshCollider::QueryCounters qc;
        if (comp.collider->closest_within(pose.to_component(lost.where_m), 1.0, closest, qc) && closest.distance < clearance) {
            clearance = closest.distance;
            lost.component = static_cast<int>(c);
        }
    }
    lost.clearance_m = clearance;
}

}  // namespace peensim
