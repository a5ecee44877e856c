#include "fem/patch_frame.h"

#include <cmath>
#include <limits>

#include "kernels/closest_point.h"

namespace peensim {

namespace {
constexpr double kSameSideCosine = 0.5;  // -, cos 60 deg: a triangle faces the patch's side
}

PatchFrame frame_from_normal(const Vec3& centre_m, const Vec3& normal) {
    PatchFrame f;
    f.centre_m = centre_m;
    f.normal = normal.normalized();
    Vec3 axis = Vec3::UnitX();
    if (std::abs(f.normal.y()) < std::abs(f.normal[0]) && std::abs(f.normal.y()) <= std::abs(f.normal.z()))
        axis = Vec3::UnitY();
    else if (std::abs(f.normal.z()) < std::abs(f.normal[0]) && std::abs(f.normal.z()) < std::abs(f.normal.y()))
        axis = Vec3::UnitZ();
    f.e1 = (axis - axis.dot(f.normal) * f.normal).normalized();
    f.e2 = f.normal.cross(f.e1);
    return f;
}

SurfacePoint closest_surface_point(const TriangleMesh& mesh, const Vec3& p, const std::vector<int>& triangles) {
    SurfacePoint best;
    best.distance_m = std::numeric_limits<double>::infinity();
    auto visit = [&](std::size_t t) {
        const Vec3 q = closest_point_on_triangle(p, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2)).point;
        const double d = (q - p).norm();
        if (d < best.distance_m) best = {q, d, static_cast<int>(t)};
    };
    if (triangles.empty())
        for (std::size_t t = 0; t < mesh.triangle_count(); ++t) visit(t);
    else
        for (int t : triangles) visit(static_cast<std::size_t>(t));
    return best;
}

PatchFrame tangent_frame(const TriangleMesh& mesh, const Vec3& centre_m, int triangle, double radius_m) {
    const Vec3 own = triangle_normal(mesh, static_cast<std::size_t>(triangle));
    Vec3 sum = Vec3::Zero();
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const Vec3 q = closest_point_on_triangle(centre_m, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2)).point;
        if ((q - centre_m).norm() > radius_m) continue;
        const Vec3 n = (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));  // 2 x area
        if (n.normalized().dot(own) < kSameSideCosine) continue;
        sum += n;
    }
    return frame_from_normal(centre_m, sum.squaredNorm() > 0.0 ? sum : own);
}

}  // namespace peensim
