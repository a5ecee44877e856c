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
#include "kernels/sphere_triangle_toi.h"
#include "kernels/toi_status.h"
#include "kernels/trajectory.h"

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
        int triangle = -1;      // index into the mesh's triangles
        double distance = 0.0;  // m
        Vec3 point;             // m, mesh frame
    };
    struct QueryCounters {
        std::uint64_t triangles_returned = 0;  // BVH leaves reached
        std::uint64_t triangles_tested = 0;    // exact closest-point tests after the plane test
    };
    bool closest_within(const Vec3& p, double radius, Closest& out, QueryCounters& counters) const;

    // The first contact in [t_begin, t_end] (s) of a sphere of `radius` (m) moving on `path`
    // (mesh frame) with any triangle: a time-ordered walk of the BVH along the swept sphere.
    // Each node gets a key, a lower bound on when the sphere can first touch anything in it (the
    // entry into its box grown by the radius, from per-axis quadratics, tightened by conservative
    // advancement; for a leaf also the entry into its plane's slab); nodes are visited in key
    // order, the walk stops once the next key is later than the best contact, and each leaf
    // reached gets the exact sphere_triangle_toi, searched only while the sphere is within reach
    // of its box. The result is what that test over all triangles would give: `overlapping` if
    // any triangle is overlapped at t_begin, else the earliest impact (ties: any of the equally
    // early triangles). A sweep whose reach meets no cell a triangle may meet (OccupiedCells) is a
    // miss without the walk. Allocates nothing; thread-safe (const, no shared scratch).
    struct Hit {
        int triangle = -1;        // index into the mesh's triangles
        TriangleContact contact;  // time (s), point (m, mesh frame), normal, feature
    };
    struct SweepCounters {
        std::uint64_t boxes_tested = 0;    // BVH nodes whose swept-sphere span was computed
        std::uint64_t nodes_visited = 0;   // BVH nodes taken from the queue (inner nodes and leaves)
        std::uint64_t leaves_visited = 0;  // triangles given the exact time-of-impact test
        std::uint64_t heap_overflows = 0;  // subtrees walked depth-first because the queue was full
        std::uint64_t windows_gated = 0;   // sweeps whose reach meets no cell a triangle may meet (no walk)
    };
    // queue_capacity: entries of the time-ordered queue (at most kFirstHitQueueCapacity); when full,
    // a subtree is walked depth-first instead, with the same answer (tests shrink it to exercise that).
    static constexpr int kFirstHitQueueCapacity = 256;
    ToiStatus first_hit(const Trajectory& path, double radius, double t_begin, double t_end, Hit& out, SweepCounters& counters,
                        int queue_capacity = kFirstHitQueueCapacity) const;

    std::size_t memory_bytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace peensim
