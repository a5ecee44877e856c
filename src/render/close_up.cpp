#include "render/close_up.h"

#include <algorithm>
#include <limits>

#include "geometry/mesh_checks.h"

namespace peensim {

std::optional<CloseUp> close_up_of(const Component& part, std::span<const double> weight, const std::string& label) {
    const TriangleMesh& mesh = *part.mesh;
    if (mesh.vertices.empty() || weight.size() != mesh.triangle_count()) return std::nullopt;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    Vec3 normal_sum = Vec3::Zero();
    double area = 0.0;  // m2
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        if (!(weight[t] > 0.0)) continue;
        const double a = weight[t] * triangle_area(mesh, t);
        normal_sum += a * triangle_normal(mesh, t);
        area += a;
        for (int k = 0; k < 3; ++k) lo = lo.cwiseMin(mesh.corner(t, k)), hi = hi.cwiseMax(mesh.corner(t, k));
    }
    if (!(area > 0.0)) return std::nullopt;
    Vec3 part_lo = mesh.vertices.front(), part_hi = part_lo;
    for (const Vec3& v : mesh.vertices) part_lo = part_lo.cwiseMin(v), part_hi = part_hi.cwiseMax(v);
    const double extent = (hi - lo).norm(), part_extent = (part_hi - part_lo).norm();  // m
    const Vec3 facing = normal_sum / area;
    if (!(extent < kCloseUpExtent * part_extent) || !(facing.norm() >= kCloseUpFacing)) return std::nullopt;
    const double margin = std::max(kCloseUpMargin * extent, part_extent / 40.0);  // m
    const Pose pose = part.kinematics.pose(SimTime{});
    CloseUp c;
    for (int corner = 0; corner < 8; ++corner) {
        Vec3 p;
        for (int k = 0; k < 3; ++k) p[k] = (corner >> k & 1) ? hi[k] + margin : lo[k] - margin;
        c.points_m.push_back(pose.to_world(p));
    }
    c.direction = -(pose.rotation * facing).normalized();
    c.name = "close-up of " + label;
    return c;
}

}  // namespace peensim
