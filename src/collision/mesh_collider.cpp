#include "collision/mesh_collider.h"

#include <btBulletCollisionCommon.h>

#include <cmath>

#include "collision/closest_point.h"

namespace peensim {

namespace {

// Collects triangle indices of the BVH leaves that overlap a box.
class CollectTriangles final : public btNodeOverlapCallback {
public:
    explicit CollectTriangles(std::vector<int>& out) : out_(out) {}
    void processNode(int /*subPart*/, int triangleIndex) override { out_.push_back(triangleIndex); }

private:
    std::vector<int>& out_;
};

}  // namespace

struct MeshCollider::Impl {
    std::vector<btScalar> vertices;   // x, y, z per vertex (m)
    std::vector<int> indices;         // 3 per triangle
    // Per triangle: unit normal and offset (n . x = d), in float to keep fine meshes small; the
    // plane test allows for their rounding (kPlaneSlack).
    struct Plane {
        float nx, ny, nz, d;
    };
    std::vector<Plane> planes;
    std::unique_ptr<btTriangleIndexVertexArray> arrays;
    std::unique_ptr<btBvhTriangleMeshShape> shape;
};

MeshCollider::MeshCollider(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
    impl_->vertices.reserve(mesh.vertices.size() * 3);
    for (const Vec3& v : mesh.vertices) {
        impl_->vertices.push_back(v.x());
        impl_->vertices.push_back(v.y());
        impl_->vertices.push_back(v.z());
    }
    impl_->indices.reserve(mesh.triangles.size() * 3);
    for (const auto& t : mesh.triangles) impl_->indices.insert(impl_->indices.end(), t.begin(), t.end());
    impl_->planes.reserve(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const Vec3 a = mesh.corner(t, 0);
        Vec3 n = (mesh.corner(t, 1) - a).cross(mesh.corner(t, 2) - a);
        n = n.norm() > 0.0 ? Vec3(n.normalized()) : Vec3::Zero();  // degenerate: never rejected
        impl_->planes.push_back({static_cast<float>(n.x()), static_cast<float>(n.y()), static_cast<float>(n.z()),
                                 static_cast<float>(n.dot(a))});
    }
    impl_->arrays = std::make_unique<btTriangleIndexVertexArray>(
        static_cast<int>(mesh.triangles.size()), impl_->indices.data(), static_cast<int>(3 * sizeof(int)),
        static_cast<int>(mesh.vertices.size()), impl_->vertices.data(), static_cast<int>(3 * sizeof(btScalar)));
    // Quantized BVH: compact nodes, the fastest traversal Bullet offers for static triangle sets.
    impl_->shape = std::make_unique<btBvhTriangleMeshShape>(impl_->arrays.get(), /*useQuantizedAabbCompression=*/true);
    // Bullet's default collision margin (0.04 m) is larger than a shot; our own tests use exact
    // distances, so the mesh carries none.
    impl_->shape->setMargin(0.0);
}

MeshCollider::~MeshCollider() = default;
MeshCollider::MeshCollider(MeshCollider&&) noexcept = default;
MeshCollider& MeshCollider::operator=(MeshCollider&&) noexcept = default;

void MeshCollider::triangles_overlapping(const Vec3& lo, const Vec3& hi, std::vector<int>& out) const {
    out.clear();
    CollectTriangles collect(out);
    impl_->shape->getOptimizedBvh()->reportAabbOverlappingNodex(&collect, btVector3(lo.x(), lo.y(), lo.z()),
                                                                 btVector3(hi.x(), hi.y(), hi.z()));
}

bool MeshCollider::closest_within(const Vec3& p, double radius, std::vector<int>& scratch, Closest& out,
                                  QueryCounters& counters) const {
    triangles_overlapping(p - Vec3::Constant(radius), p + Vec3::Constant(radius), scratch);
    counters.triangles_returned += scratch.size();
    // Float planes: rounding of the normal (~6e-8) times coordinates up to ~1 m, plus the offset's.
    constexpr double kPlaneSlack = 1e-6;  // m
    const double reject = radius + kPlaneSlack;
    double best = radius * radius;
    const int* idx = impl_->indices.data();
    const btScalar* v = impl_->vertices.data();
    for (int t : scratch) {
        const Impl::Plane& pl = impl_->planes[static_cast<std::size_t>(t)];
        const double h = pl.nx * p.x() + pl.ny * p.y() + pl.nz * p.z() - pl.d;
        if (h > reject || h < -reject) continue;
        ++counters.triangles_tested;
        const int* tri = idx + 3 * t;
        const Vec3 a(v[3 * tri[0]], v[3 * tri[0] + 1], v[3 * tri[0] + 2]);
        const Vec3 b(v[3 * tri[1]], v[3 * tri[1] + 1], v[3 * tri[1] + 2]);
        const Vec3 c(v[3 * tri[2]], v[3 * tri[2] + 1], v[3 * tri[2] + 2]);
        const Vec3 cp = closest_point_on_triangle(p, a, b, c).point;
        const double d2 = (p - cp).squaredNorm();
        if (d2 < best) {
            best = d2;
            out.triangle = t;
            out.point = cp;
        }
    }
    if (best >= radius * radius) return false;
    out.distance = std::sqrt(best);
    return true;
}

std::size_t MeshCollider::memory_bytes() const {
    btOptimizedBvh* bvh = impl_->shape->getOptimizedBvh();
    const std::size_t nodes = bvh ? static_cast<std::size_t>(bvh->getQuantizedNodeArray().size()) : 0;
    return impl_->vertices.size() * sizeof(btScalar) + impl_->indices.size() * sizeof(int) +
           impl_->planes.size() * sizeof(Impl::Plane) +
           nodes * sizeof(btQuantizedBvhNode);
}

}  // namespace peensim
