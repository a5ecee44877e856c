#include "collision/mesh_collider.h"

#include <btBulletCollisionCommon.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "collision/occupied_cells.h"
#include "kernels/closest_point.h"
#include "kernels/swept_sphere_box.h"

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
    std::vector<btScalar> vertices;         // x, y, z per vertex (m): what our exact tests use
    std::vector<btScalar> bullet_vertices;  // the same times kBulletScale: what Bullet's BVH is built on
    std::vector<int> indices;               // 3 per triangle
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
    // The cells a triangle may meet: a search window whose bounds meet none is a miss without the
    // BVH walk (the open cavity of a chamber, where the walk cannot end at the root).
    std::unique_ptr<OccupiedCells> cells;
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
        impl_->planes.push_back(
            {static_cast<float>(n.x()), static_cast<float>(n.y()), static_cast<float>(n.z()), static_cast<float>(n.dot(a))});
    }
    impl_->arrays = std::make_unique<btTriangleIndexVertexArray>(static_cast<int>(mesh.triangles.size()), impl_->indices.data(),
                                                                 static_cast<int>(3 * sizeof(int)), static_cast<int>(mesh.vertices.size()),
                                                                 impl_->bullet_vertices.data(), static_cast<int>(3 * sizeof(btScalar)));
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
    impl_->cells = std::make_unique<OccupiedCells>(mesh);
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

ToiStatus MeshCollider::first_hit(const Trajectory& path, double radius, double t_begin, double t_end, Hit& out, SweepCounters& counters,
                                  int queue_capacity) const {
    // Best-first in time. Leaves are tested in key order and the walk stops once the next key is
    // later than the best contact, so the cost follows the few triangles the sphere can reach
    // first, not every triangle within R of its path (what an overlap query would return).
    // The keys are what keep that set small: with the bare box entry, every leaf within R of the
    // contact on a fine surface met at a shallow angle is entered (along the box axes) before the
    // contact itself and would be tested.
    if (!(t_end >= t_begin)) return ToiStatus::miss;
    const btQuantizedBvhNode* nodes = &impl_->shape->getOptimizedBvh()->getQuantizedNodeArray()[0];
    const Vec3& origin = impl_->quantization_origin;
    const Vec3& step = impl_->quantization_step;
    const int* idx = impl_->indices.data();
    const btScalar* v = impl_->vertices.data();
    auto vertex = [&](int i) { return Vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]); };

    SweptSphere swept(path, radius, t_begin, t_end);
    // No triangle within the sweep's reach (its centre's bounds grown by the radius and the pad,
    // the box every node's span is first tested against): nothing to walk.
    if (!impl_->cells->any_in(swept.reach_lo(), swept.reach_hi())) {
        ++counters.windows_gated;
        return ToiStatus::miss;
    }
    ToiStatus status = ToiStatus::miss;
    double best = t_end;
    double top_speed = path.max_speed(t_begin, t_end);  // m/s, over [t_begin, best]

    struct Queued {
        double key;   // s, no contact with the node's triangles before this
        double last;  // s, the sphere is out of reach of the node's box after this
        int node;
    };
    // Fills q and returns true if the node can hold a contact no later than `best`.
    auto reach = [&](int i, Queued& q) {
        ++counters.boxes_tested;
        const btQuantizedBvhNode& node = nodes[i];
        Vec3 lo, hi;
        for (int k = 0; k < 3; ++k) {
            lo[k] = origin[k] + step[k] * node.m_quantizedAabbMin[k];
            hi[k] = origin[k] + step[k] * node.m_quantizedAabbMax[k];
        }
        TimeSpan span;
        if (!swept.span(lo, hi, span)) return false;
        double key = span.first;
        if (!node.isLeafNode()) {
            for (int step_count = 0; step_count < 2; ++step_count) {  // conservative advancement
                const Vec3 p = path.position(key);
                double d2 = 0.0;
                for (int k = 0; k < 3; ++k) {
                    const double e = p[k] < lo[k] ? lo[k] - p[k] : (p[k] > hi[k] ? p[k] - hi[k] : 0.0);
                    d2 += e * e;
                }
                const double gap = std::sqrt(d2) - radius - swept.pad();
                if (gap <= 0.0) break;
                if (top_speed == 0.0) return false;
                key += gap / top_speed;
                if (key > best || key > span.last) return false;
            }
        } else {
            // A leaf: also within reach of the triangle's plane (exact, a quadratic), then two
            // steps of advancement towards the triangle itself. On a fine surface met at a
            // shallow angle, the neighbours ahead of the contact are entered (box and plane)
            // before it, but lie a sideways run away: the advancement puts them after it.
            const int* tri = idx + 3 * node.getTriangleIndex();
            const Vec3 a = vertex(tri[0]), b = vertex(tri[1]), c = vertex(tri[2]);
            Vec3 n = (b - a).cross(c - a);
            const double n_len = n.norm();
            if (n_len > 0.0) {
                n /= n_len;
                TimeSpan slab;
                if (!swept.slab_span(n, n.dot(a), n.dot(a), slab)) return false;
                span.first = std::max(span.first, slab.first);
                span.last = std::min(span.last, slab.last);
                if (span.first > span.last) return false;
                key = span.first;
            }
            for (int step_count = 0; step_count < 2; ++step_count) {
                const Vec3 p = path.position(key);
                const double gap = (p - closest_point_on_triangle(p, a, b, c).point).norm() - radius - swept.pad();
                if (gap <= 0.0) break;
                if (top_speed == 0.0) return false;
                key += gap / top_speed;
                if (key > best || key > span.last) return false;
            }
        }
        if (key > best || key > span.last) return false;
        q = {key, span.last, i};
        return true;
    };

    // The exact test of one leaf, searched only from its key to the last moment the sphere is
    // within reach of its box. True once an overlap ends the walk.
    auto test_leaf = [&](const Queued& q) {
        ++counters.leaves_visited;
        const int t = nodes[q.node].getTriangleIndex();
        const int* tri = idx + 3 * t;
        const Vec3 a = vertex(tri[0]), b = vertex(tri[1]), c = vertex(tri[2]);
        const double until = std::min(best, q.last);
        TriangleContact contact;
        ToiStatus found;
        if (q.key <= t_begin) {
            // Within reach from the start: read the state at t_begin (overlap, touching).
            found = sphere_triangle_toi(path, radius, a, b, c, t_begin, until, contact);
        } else {
            // Clear of the triangle until the key, so the search alone is exact.
            found = sphere_triangle_first_touch(path, radius, a, b, c, q.key, until, contact) ? ToiStatus::impact : ToiStatus::miss;
        }
        if (found == ToiStatus::overlapping) {
            out = {t, contact};
            status = ToiStatus::overlapping;
            return true;
        }
        if (found == ToiStatus::impact && (status == ToiStatus::miss || contact.time < best)) {
            out = {t, contact};
            status = ToiStatus::impact;
            best = contact.time;
            swept.shorten(best);
            top_speed = path.max_speed(t_begin, best);
        }
        return false;
    };
    auto children = [&](int i, int& left, int& right) {
        left = i + 1;
        right = left + (nodes[left].isLeafNode() ? 1 : nodes[left].getEscapeIndex());
    };

    // If the queue is full (a wide front of nodes reachable at once, e.g. a sphere skimming a
    // fine surface), that subtree is walked at once, depth first, earlier child first: still exact.
    constexpr int kMaxDepth = 256;
    auto walk_subtree = [&](const Queued& start) {
        ++counters.heap_overflows;
        Queued stack[kMaxDepth];
        int top = 0;
        stack[top++] = start;
        while (top > 0) {
            const Queued q = stack[--top];
            if (q.key > best) continue;
            ++counters.nodes_visited;
            if (nodes[q.node].isLeafNode()) {
                if (test_leaf(q)) return true;
                continue;
            }
            int left, right;
            children(q.node, left, right);
            Queued ql, qr;
            const bool has_l = reach(left, ql), has_r = reach(right, qr);
            if (top + 2 > kMaxDepth) throw std::runtime_error("MeshCollider: BVH deeper than expected");
            if (has_l && has_r) {
                stack[top++] = ql.key <= qr.key ? qr : ql;
                stack[top++] = ql.key <= qr.key ? ql : qr;
            } else if (has_l) {
                stack[top++] = ql;
            } else if (has_r) {
                stack[top++] = qr;
            }
        }
        return false;
    };

    const int capacity = std::clamp(queue_capacity, 1, kFirstHitQueueCapacity);
    Queued heap[kFirstHitQueueCapacity];
    int size = 0;
    auto later = [](const Queued& x, const Queued& y) { return x.key > y.key; };  // a min-heap on the key
    if (!reach(0, heap[0])) return ToiStatus::miss;
    size = 1;
    while (size > 0) {
        std::pop_heap(heap, heap + size, later);
        const Queued q = heap[--size];
        if (q.key > best) break;  // every node left is reachable only after the best contact
        ++counters.nodes_visited;
        if (nodes[q.node].isLeafNode()) {
            if (test_leaf(q)) return status;
            continue;
        }
        int child[2];
        children(q.node, child[0], child[1]);
        for (int i : child) {
            Queued entry;
            if (!reach(i, entry)) continue;
            if (size < capacity) {
                heap[size++] = entry;
                std::push_heap(heap, heap + size, later);
            } else if (walk_subtree(entry)) {
                return status;
            }
        }
    }
    return status;
}

std::size_t MeshCollider::memory_bytes() const {
    btOptimizedBvh* bvh = impl_->shape->getOptimizedBvh();
    const std::size_t nodes = bvh ? static_cast<std::size_t>(bvh->getQuantizedNodeArray().size()) : 0;
    return 2 * impl_->vertices.size() * sizeof(btScalar) + impl_->indices.size() * sizeof(int) +
           impl_->planes.size() * sizeof(Impl::Plane) + nodes * sizeof(btQuantizedBvhNode) + impl_->cells->memory_bytes();
}

}  // namespace peensim
