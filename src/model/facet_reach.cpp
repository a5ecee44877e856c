#include "model/facet_reach.h"

#include <algorithm>
#include <cmath>

#include "geometry/mesh_checks.h"
#include "geometry/triangle_sampling.h"

namespace peensim {

namespace {

constexpr double kClearanceFactor = 1.05;  // -, the probe centre's distance from the surface in shot radii

}  // namespace

bool shot_fits_beside(const Model& model, ShotCavity* cavity, const Component& c, const Vec3& x, const Vec3& n, double R) {
    for (double side : {1.0, -1.0}) {
        if (side < 0.0 && c.solid) break;  // a solid's outside is the side its normals point to
        const Vec3 centre = x + side * kClearanceFactor * R * n;
        if ((cavity == nullptr || cavity->contains(centre)) && clear_of_meshes(model, centre, R)) return true;
    }
    return false;
}

std::vector<double> reachable_fractions(const Model& model, std::size_t ci, ShotCavity* cavity) {
    const Component& c = model.components[ci];
    const Pose pose = c.kinematics.pose(SimTime{});
    const double R = model.min_shot_radius_m;  // the smallest shot of a mix reaches furthest
    const TriangleMesh& mesh = *c.mesh;
    std::vector<double> reach(mesh.triangle_count(), 0.0);
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const double probes =
            std::clamp(std::ceil(triangle_area(mesh, t) / (4.0 * R * R)), 1.0, 1.0 * kReachProbesPerEdge * kReachProbesPerEdge);
        const int n = static_cast<int>(std::ceil(std::sqrt(probes)));
        const Vec3 normal = pose.rotation * triangle_normal(mesh, t);
        int reached = 0, total = 0;
        for_each_sub_centroid(mesh, t, n, [&](const Vec3& p) {
            ++total;
            reached += shot_fits_beside(model, cavity, c, pose.to_world(p), normal, R) ? 1 : 0;
        });
        reach[t] = static_cast<double>(reached) / total;
    }
    return reach;
}

std::function<bool(const Vec3&, std::size_t, double)> reach_test(const Model& model, std::size_t ci, ShotCavity* cavity) {
    const Component& c = model.components[ci];
    const Pose pose = c.kinematics.pose(SimTime{});
    return [&model, &c, cavity, pose](const Vec3& p, std::size_t t, double R) {
        return shot_fits_beside(model, cavity, c, pose.to_world(p), pose.rotation * triangle_normal(*c.mesh, t), R);
    };
}

}  // namespace peensim
