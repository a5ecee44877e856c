#include "collision/mesh_collider.h"

#include <btBulletCollisionCommon.h>

#include <cmath>
#include <stdexcept>

#include "collision/closest_point.h"

namespace peensim {

namespace {

// Bullet builds every BVH leaf box at least 0.002 units wide (MIN_AABB_DIMENSION in
// btQuantizedBvh.cpp, a metre-scale assumption): on a mesh in metres every triangle under 2 mm
// gets a 2 mm box, and a query near a fine mesh visits hundreds of leaves. The BVH is therefore
// built on coordinates in millimetres (times 1000), which makes that floor 2 um.
constexpr double kBulletScale = 1000.0;  // Bullet units per metre

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
    std::vector<btScalar> vertices;   // x, y, z per vertex (m): what our exact tests use
    std::vector<btScalar> bullet_vertices;  // the same times kBulletScale: what Bullet's BVH is built on
    std::vector<int> indices;         // 3 per triangle
    // Per triangle: unit normal and offset (n . x = d), in float to keep fine meshes small; the
    // plane test allows for their rounding (kPlaneSlack).
    struct Plane {
        float nx, ny, nz, d;
    };
    std::vector<Plane> planes;
    // Bullet's quantization of node boxes: coordinate = origin + step * quantized (m).
    Vec3 quantization_origin = Vec3::Zero();
    Vec3 quantization_step = Vec3::Zero();
    std::unique_ptr<btTriangleIndexVertexArray> arrays;
    std::unique_ptr<btBvhTriangleMeshShape> shape;
};

MeshCollider::MeshCollider(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
    impl_->vertices.reserve(mesh.vertices.size() * 3);
    impl_->bullet_vertices.reserve(mesh.vertices.size() * 3);
    for (const Vec3& v : mesh.vertices) {
        for (int k = 0; k < 3; ++k) {
            impl_->vertices.push_back(v[k]);
            impl_->bullet_vertices.push_back(v[k] * kBulletScale);
        }
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
        static_cast<int>(mesh.vertices.size()), impl_->bullet_vertices.data(), static_cast<int>(3 * sizeof(btScalar)));
    // Quantized BVH: compact nodes, the fastest traversal Bullet offers for static triangle sets.
    impl_->shape = std::make_unique<btBvhTriangleMeshShape>(impl_->arrays.get(), /*useQuantizedAabbCompression=*/true);
    // Bullet's default collision margin (0.04 m) is larger than a shot; our own tests use exact
    // distances, so the mesh carries none.
    impl_->shape->setMargin(0.0);
    const btOptimizedBvh* bvh = impl_->shape->getOptimizedBvh();
    const unsigned short zero[3] = {0, 0, 0}, one[3] = {1, 1, 1};
    const btVector3 o = bvh->unQuantize(zero), o1 = bvh->unQuantize(one);
    impl_->quantization_origin = Vec3(o.x(), o.y(), o.z()) / kBulletScale;
    impl_->quantization_step = Vec3(o1.x() - o.x(), o1.y() - o.y(), o1.z() - o.z()) / kBulletScale;
}

MeshCollider::~MeshCollider() = default;
MeshCollider::MeshCollider(MeshCollider&&) noexcept = default;
MeshCollider& MeshCollider::operator=(MeshCollider&&) noexcept = default;

void MeshCollider::triangles_overlapping(const Vec3& lo, const Vec3& hi, std::vector<int>& out) const {
    out.clear();
    CollectTriangles collect(out);
    const Vec3 l = lo * kBulletScale, h = hi * kBulletScale;
    impl_->shape->getOptimizedBvh()->reportAabbOverlappingNodex(&collect, btVector3(l.x(), l.y(), l.z()), btVector3(h.x(), h.y(), h.z()));
}

bool MeshCollider::closest_within(const Vec3& p, double radius, Closest& out, QueryCounters& counters) const {
    // Nearest-first descent of Bullet's quantized BVH, pruning every node farther than the best
    // triangle found so far: the cost follows the few triangles near the closest point, not all
    // triangles within `radius` (hundreds on a fine mesh), so it stays flat in the triangle count.
    // Bullet's own walk (reportAabbOverlappingNodex) visits every leaf in the query box.
    const btQuantizedBvhNode* nodes = &impl_->shape->getOptimizedBvh()->getQuantizedNodeArray()[0];
    const Vec3& origin = impl_->quantization_origin;
    const Vec3& step = impl_->quantization_step;
    auto box_distance2 = [&](const btQuantizedBvhNode& node) {
        double d2 = 0.0;
        for (int k = 0; k < 3; ++k) {
            const double lo = origin[k] + step[k] * node.m_quantizedAabbMin[k];
            const double hi = origin[k] + step[k] * node.m_quantizedAabbMax[k];
            const double e = p[k] < lo ? lo - p[k] : (p[k] > hi ? p[k] - hi : 0.0);
            d2 += e * e;
        }
        return d2;
    };
    // Float planes: rounding of the normal (~6e-8) times coordinates up to ~1 m, plus the offset's.
    constexpr double kPlaneSlack = 1e-6;  // m
    const int* idx = impl_->indices.data();
    const btScalar* v = impl_->vertices.data();
    double best = radius * radius;
    bool found = false;
    constexpr int kMaxDepth = 256;
    int stack[kMaxDepth];
    int top = 0;
    if (box_distance2(nodes[0]) < best) stack[top++] = 0;
    while (top > 0) {
        const int i = stack[--top];
        const btQuantizedBvhNode& node = nodes[i];
        if (box_distance2(node) >= best) continue;  // the best shrank since this node was pushed
        if (node.isLeafNode()) {
            const int t = node.getTriangleIndex();
            ++counters.triangles_returned;
            const Impl::Plane& pl = impl_->planes[static_cast<std::size_t>(t)];
            const double h = pl.nx * p.x() + pl.ny * p.y() + pl.nz * p.z() - pl.d;
            const double reach = std::sqrt(best) + kPlaneSlack;
            if (h > reach || h < -reach) continue;
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
                found = true;
            }
            continue;
        }
        const int left = i + 1;
        const int right = left + (nodes[left].isLeafNode() ? 1 : nodes[left].getEscapeIndex());
        const double dl = box_distance2(nodes[left]), dr = box_distance2(nodes[right]);
        if (top + 2 > kMaxDepth) throw std::runtime_error("MeshCollider: BVH deeper than expected");
        // Push the farther child first so the nearer one is explored first.
        if (dl <= dr) {
            if (dr < best) stack[top++] = right;
            if (dl < best) stack[top++] = left;
        } else {
            if (dl < best) stack[top++] = left;
            if (dr < best) stack[top++] = right;
        }
    }
    if (!found) return false;
    out.distance = std::sqrt(best);
    return true;
}

std::size_t MeshCollider::memory_bytes() const {
    btOptimizedBvh* bvh = impl_->shape->getOptimizedBvh();
    const std::size_t nodes = bvh ? static_cast<std::size_t>(bvh->getQuantizedNodeArray().size()) : 0;
    return 2 * impl_->vertices.size() * sizeof(btScalar) + impl_->indices.size() * sizeof(int) +
           impl_->planes.size() * sizeof(Impl::Plane) +
           nodes * sizeof(btQuantizedBvhNode);
}

}  // namespace peensim
