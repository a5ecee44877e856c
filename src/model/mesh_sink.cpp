#include "model/mesh_sink.h"

#include <cmath>
#include <stdexcept>

#include "geometry/mesh_checks.h"

namespace peensim {

MeshSink::MeshSink(std::string name, std::shared_ptr<const TriangleMesh> mesh) : name_(std::move(name)), mesh_(std::move(mesh)) {
    const EdgeReport edges = edge_report(*mesh_);
    if (mesh_->triangle_count() == 0 || edges.boundary_edges != 0 || edges.non_manifold_edges != 0)
        throw std::invalid_argument("a mesh sink must be a closed mesh (every edge shared by exactly two triangles); this one has " +
                                    std::to_string(edges.boundary_edges) + " open and " + std::to_string(edges.non_manifold_edges) +
                                    " non-manifold edges");
    collider_ = std::make_unique<MeshCollider>(*mesh_);
    lo_ = hi_ = mesh_->vertices.front();
    for (const Vec3& v : mesh_->vertices) lo_ = lo_.cwiseMin(v), hi_ = hi_.cwiseMax(v);
}

double MeshSink::winding_number(const Vec3& p) const {
    // Van Oosterom and Strackee's solid angle of each triangle seen from p.
    double sum = 0.0;
    for (std::size_t t = 0; t < mesh_->triangle_count(); ++t) {
        const Vec3 a = mesh_->corner(t, 0) - p, b = mesh_->corner(t, 1) - p, c = mesh_->corner(t, 2) - p;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        const double numerator = a.dot(b.cross(c));
        const double denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
        sum += 2.0 * std::atan2(numerator, denominator);
    }
    return sum / (4.0 * M_PI);
}

bool MeshSink::contains(const Vec3& p) const {
    if ((p.array() < lo_.array()).any() || (p.array() > hi_.array()).any()) return false;
    return std::abs(winding_number(p)) > 0.5;
}

std::optional<double> MeshSink::first_entry(const Trajectory& path, double ta, double tb) const {
    if (contains(path.position(ta))) return ta;
    MeshCollider::Hit hit;
    MeshCollider::SweepCounters counters;
    switch (collider_->first_hit(path, kSurfaceReach, ta, tb, hit, counters)) {
        case ToiStatus::impact: return hit.contact.time;
        case ToiStatus::overlapping: return ta;  // on the surface now
        case ToiStatus::miss: break;
    }
    return std::nullopt;
}

}  // namespace peensim
