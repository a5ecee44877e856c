#include "engine/moving_mesh_gap.h"

#include <algorithm>
#include <cmath>

namespace peensim {

namespace {

// -, the most the shot may close in on the surface between two gap samples, as a fraction of R.
constexpr double kSampleTravel = 0.125;

}  // namespace

MovingMeshGap::MovingMeshGap(const Component& component, const SimTime& step_start, const StepArc& arc, double radius_m, double u_from,
                             StepStats& stats)
    : component_(component), t0_(step_start), arc_(arc), radius_m_(radius_m), stats_(stats) {
    const Kinematics& kin = component.kinematics;
    const double span = std::max(0.0, arc.dt - u_from);  // s
    // The velocity is linear in time, so its norm is largest at an end of the span.
    const double v_max = std::max(arc.velocity(u_from).norm(), arc.v_end.norm());       // m/s
    const double axis_distance = (arc.p_end - kin.axis_point_m).norm() + v_max * span;  // m, at most, over the span
    const double closing = v_max + std::abs(kin.omega_rad_per_s) * axis_distance;       // m/s, bound on |d gap / du|
    reach_m_ = radius_m + closing * span + kSampleTravel * radius_m;
    sample_interval_s_ = closing > 0.0 ? kSampleTravel * radius_m / closing : std::max(span, 1e-300);
}

double MovingMeshGap::operator()(double u) const {
    const Vec3 q = component_.kinematics.pose(t0_, u).to_component(arc_.centre(u));
    MeshCollider::Closest closest;
    MeshCollider::QueryCounters counters;
    const bool found = component_.collider->closest_within(q, reach_m_, closest, counters);
    ++stats_.bvh_queries;
    stats_.triangle_tests += counters.triangles_tested;
    stats_.triangles_returned += counters.triangles_returned;
    return (found ? closest.distance : reach_m_) - radius_m_;
}

MovingMeshGap::Touch MovingMeshGap::touch_at(double u) const {
    const Pose pose = component_.kinematics.pose(t0_, u);
    const Vec3 q = pose.to_component(arc_.centre(u));
    MeshCollider::Closest closest;
    MeshCollider::QueryCounters counters;
    // The touch time was bracketed with the gap at most 0 there: something is within R.
    if (!component_.collider->closest_within(q, reach_m_, closest, counters)) closest.distance = -1.0;
    ++stats_.bvh_queries;
    stats_.triangle_tests += counters.triangles_tested;
    stats_.triangles_returned += counters.triangles_returned;
    Touch out;
    out.mesh_triangle = closest.triangle;
    if (closest.distance > 1e-9 * radius_m_) {
        out.normal = pose.rotation * ((q - closest.point) / closest.distance);
        out.point = pose.to_world(closest.point);
        return out;
    }
    // Centre on the surface (or nothing found, which the bracket rules out): the face normal on the
    // side the shot comes from, relative to the turning surface.
    const TriangleMesh& mesh = *component_.mesh;
    const auto t = static_cast<std::size_t>(std::max(0, closest.triangle));
    Vec3 n_local = (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0)).normalized();
    const Vec3 c_world = arc_.centre(u);
    const Vec3 v_rel = arc_.velocity(u) - component_.kinematics.point_velocity(c_world, t0_, u);
    if (n_local.dot(pose.rotation.transpose() * v_rel) > 0.0) n_local = -n_local;
    out.normal = pose.rotation * n_local;
    out.point = closest.triangle >= 0 ? pose.to_world(closest.point) : c_world - radius_m_ * out.normal;
    out.mesh_triangle = static_cast<int>(t);
    return out;
}

}  // namespace peensim
