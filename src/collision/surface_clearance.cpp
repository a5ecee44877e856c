#include "collision/surface_clearance.h"

#include "kernels/closest_point.h"

namespace peensim {

SurfaceClearance surface_clearance(const TriangleMesh& mesh, bool solid, const Vec3& p, const MeshCollider::Closest& closest) {
    const auto t = static_cast<std::size_t>(closest.triangle);
    const Vec3& a = mesh.corner(t, 0);
    const Vec3 face = (mesh.corner(t, 1) - a).cross(mesh.corner(t, 2) - a);
    const Vec3 d = p - closest.point;
    SurfaceClearance out;
    out.distance_m = closest.distance;
    if (closest.distance > 0.0)
        out.normal = d / closest.distance;
    else if (face.norm() > 0.0)
        out.normal = face.normalized();
    if (!solid || !(face.dot(d) < 0.0)) return out;
    if (closest_point_on_triangle(p, a, mesh.corner(t, 1), mesh.corner(t, 2)).feature != TriangleFeature::face) return out;
    out.distance_m = -closest.distance;
    out.normal = face.normalized();
    return out;
}

}  // namespace peensim
