// Bullet's BVH over one component's triangle mesh (btBvhTriangleMeshShape, quantized),
// built once at load. Queried in the component's own frame, so a moving component
// (vibrating sonotrode, rotating part) never needs a refit. Bullet stays behind this
// interface: callers get our triangle indices, never Bullet types.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "common/vec.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

class MeshCollider {
public:
    explicit MeshCollider(const TriangleMesh& mesh);
    ~MeshCollider();
    MeshCollider(MeshCollider&&) noexcept;
    MeshCollider& operator=(MeshCollider&&) noexcept;

    // Appends to `out` (cleared first) the triangles whose bounding boxes overlap [lo, hi]
    // (mesh frame, m). `out` is reused by the caller, so a query allocates nothing once warm.
    void triangles_overlapping(const Vec3& lo, const Vec3& hi, std::vector<int>& out) const;

    // The point of the mesh closest to p (mesh frame, m) if it lies within `radius` (m): a
    // nearest-first descent of the BVH that prunes every node farther than the best triangle so
    // far; a plane test rejects most leaves cheaply, the exact closest point decides the rest.
    // Allocates nothing.
    struct Closest {
        int triangle = -1;     // index into the mesh's triangles
        double distance = 0.0; // m
        Vec3 point;            // m, mesh frame
    };
    struct QueryCounters {
        std::uint64_t triangles_returned = 0;  // BVH leaves reached
        std::uint64_t triangles_tested = 0;    // exact closest-point tests after the plane test
    };
    bool closest_within(const Vec3& p, double radius, Closest& out, QueryCounters& counters) const;

    std::size_t memory_bytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace peensim
