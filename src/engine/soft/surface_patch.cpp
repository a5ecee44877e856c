#include "engine/soft/surface_patch.h"

#include <algorithm>
#include <cmath>

#include "kernels/closest_point.h"

namespace peensim {

void SurfacePatch::overlaps(const Vec3& p, double R, double margin_m, const MeshCollider& collider, const TriangleMesh& mesh,
                            std::vector<SurfaceOverlap>& out) {
    if (!valid_ || (p - centre_).norm() + R > reach_) {
        // Every triangle whose box comes within R + margin of p: all that can touch the sphere while
        // its centre stays within the margin of here.
        centre_ = p;
        reach_ = R + margin_m;
        const Vec3 r = Vec3::Constant(reach_);
        collider.triangles_overlapping(p - r, p + r, triangles_);
        nearby_.clear();
        for (const int t : triangles_) {
            const std::size_t k = static_cast<std::size_t>(t);
            Nearby n{t, mesh.corner(k, 0), mesh.corner(k, 1), mesh.corner(k, 2), Vec3::Zero(), Vec3::Zero(), 0.0};
            const Vec3 cross = (n.b - n.a).cross(n.c - n.a);
            if (cross.norm() > 0.0) n.normal = cross.normalized();
            n.centre = (n.a + n.b + n.c) / 3.0;
            n.radius = std::max({(n.a - n.centre).norm(), (n.b - n.centre).norm(), (n.c - n.centre).norm()});
            nearby_.push_back(n);
        }
        valid_ = true;
        empty_ = nearby_.empty();
    }
    if (empty_) return;
    found_.clear();
    for (const Nearby& n : nearby_) {
        // Its plane first (rules out a large face the sphere is nowhere near), then its bounding sphere.
        if (std::abs(n.normal.dot(p - n.a)) >= R) continue;
        const double reach = R + n.radius;
        if ((p - n.centre).squaredNorm() >= reach * reach) continue;
        const int t = n.triangle;
        const ClosestPoint c = closest_point_on_triangle(p, n.a, n.b, n.c);
        const Vec3 d = p - c.point;
        const double dist2 = d.squaredNorm();
        if (!(dist2 < R * R) || !(dist2 > 0.0)) continue;
        const double dist = std::sqrt(dist2);
        found_.push_back({t, c.point, d / dist, R - dist});
    }
    if (found_.empty()) return;
    // Deepest first (ties by triangle, so the order never depends on the BVH's), then one per direction.
    std::sort(found_.begin(), found_.end(), [](const SurfaceOverlap& a, const SurfaceOverlap& b) {
        return a.depth_m > b.depth_m || (a.depth_m == b.depth_m && a.mesh_triangle < b.mesh_triangle);
    });
    const std::size_t first = out.size();
    for (const SurfaceOverlap& o : found_) {
        bool same = false;
        for (std::size_t k = first; k < out.size() && !same; ++k) same = out[k].normal.dot(o.normal) > kSameContactCos;
        if (!same) out.push_back(o);
    }
}

}  // namespace peensim
