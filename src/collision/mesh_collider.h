// Bullet's BVH over one component's triangle mesh (btBvhTriangleMeshShape, quantized),
// built once at load. Queried in the component's own frame, so a moving component
// (vibrating sonotrode, rotating part) never needs a refit. Bullet stays behind this
// interface: callers get our triangle indices, never Bullet types.
#pragma once

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

    std::size_t memory_bytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace peensim
