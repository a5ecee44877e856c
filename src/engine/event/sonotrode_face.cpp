#include "engine/event/sonotrode_face.h"

#include <cmath>
#include <limits>

namespace peensim {

namespace {

constexpr double kParallel = 1e-12;  // 1 - cos of the largest angle between a face normal and `up` (~1.4e-6 rad)
constexpr double kCoplanar = 1e-9;   // m, largest offset of a face triangle from the face plane

}  // namespace

SonotrodeFace build_sonotrode_face(const Component& sonotrode, const Vec3& up) {
    const TriangleMesh& mesh = *sonotrode.mesh;
    const Pose& rest = sonotrode.kinematics.rest;
    const Vec3 up_c = rest.rotation.transpose() * up;  // `up` in the sonotrode's frame
    SonotrodeFace out;
    out.on_face.assign(mesh.triangle_count(), 0);
    // The highest plane among triangles facing along `up` (either winding).
    double top = -std::numeric_limits<double>::infinity();
    std::vector<double> height(mesh.triangle_count(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const Vec3 n = (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
        const double len = n.norm();
        if (!(len > 0.0) || std::abs(n.dot(up_c)) / len < 1.0 - kParallel) continue;
        height[t] = up_c.dot(mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0;
        top = std::max(top, height[t]);
    }
    auto rest_mesh = std::make_shared<TriangleMesh>();
    rest_mesh->vertices = mesh.vertices;
    rest_mesh->group_names = mesh.group_names;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        if (std::abs(height[t] - top) <= kCoplanar) {
            out.on_face[t] = 1;
            ++out.face_triangles;
            continue;
        }
        rest_mesh->triangles.push_back(mesh.triangles[t]);
        rest_mesh->source_facet.push_back(mesh.source_facet.empty() ? static_cast<int>(t) : mesh.source_facet[t]);
        if (!mesh.group_of_triangle.empty()) rest_mesh->group_of_triangle.push_back(mesh.group_of_triangle[t]);
    }
    if (!rest_mesh->triangles.empty()) {
        out.rest_collider = std::make_shared<MeshCollider>(*rest_mesh);
        out.rest_mesh = std::move(rest_mesh);
    }
    const Kinematics& k = sonotrode.kinematics;
    out.plane.normal = up;
    out.plane.point_m = rest.to_world(top * up_c);
    out.plane.axis = k.axis;
    out.plane.amplitude_m = k.amplitude_m;
    out.plane.frequency_hz = k.frequency_hz;
    out.plane.phase_rad = k.phase_rad;
    return out;
}

bool SonotrodeFace::contains(const Component& sonotrode, const Vec3& point_component, double tolerance, int& triangle) const {
    MeshCollider::Closest closest;
    MeshCollider::QueryCounters counters;
    if (!sonotrode.collider->closest_within(point_component, tolerance, closest, counters)) return false;
    triangle = closest.triangle;
    return true;
}

}  // namespace peensim
