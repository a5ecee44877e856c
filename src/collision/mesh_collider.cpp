#include "collision/mesh_collider.h"

#include <btBulletCollisionCommon.h>

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

std::size_t MeshCollider::memory_bytes() const {
    btOptimizedBvh* bvh = impl_->shape->getOptimizedBvh();
    const std::size_t nodes = bvh ? static_cast<std::size_t>(bvh->getQuantizedNodeArray().size()) : 0;
    return impl_->vertices.size() * sizeof(btScalar) + impl_->indices.size() * sizeof(int) +
           nodes * sizeof(btQuantizedBvhNode);
}

}  // namespace peensim
