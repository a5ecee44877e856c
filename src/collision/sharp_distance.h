// A sharper lower bound of the distance from a point to a mesh than the DistanceGate's, for the
// points the gate cannot rule out (those within a few cells of the surface). The exact distance
// from each such cell's centre to the mesh is found once, with the BVH, the first time a shot
// comes near that cell, and kept; the distance function being 1-Lipschitz, a point p of the cell
// is then at least d(centre) - |p - centre| from the mesh. On fine meshes this removes most BVH
// queries (they return hundreds of triangles there) for shot passing near but not touching.
//
// This is a cache, so it lives with the stepping scheme's mutable state, not in the model; its
// values depend only on the geometry, so results do not depend on when they were computed.
#pragma once

#include <vector>

#include "collision/distance_gate.h"
#include "collision/mesh_collider.h"

namespace peensim {

class SharpDistance {
public:
    // reach_m: the largest query radius callers will test against (m); distances beyond
    // reach + half a cell diagonal are not resolved.
    SharpDistance(const DistanceGate& gate, const MeshCollider& collider, double reach_m);

    // Lower bound (m) of the distance from p (mesh frame) to the mesh.
    double lower_bound(const Vec3& p) {
        const double coarse = gate_->lower_bound(p);
        if (coarse > reach_) return coarse;
        int i, j, k;
        if (!gate_->cell_of(p, i, j, k)) return coarse;
        const std::size_t id = gate_->cell_index(i, j, k);
        float& d = centre_distance_[id];
        const Vec3 c = gate_->cell_centre(i, j, k);
        if (d < 0.0f) d = exact_distance(c);
        return std::max(coarse, static_cast<double>(d) - (p - c).norm());
    }

    std::size_t cells_resolved() const { return resolved_; }

private:
    float exact_distance(const Vec3& centre);

    const DistanceGate* gate_;
    const MeshCollider* collider_;
    double reach_;                        // m
    double resolve_;                      // m, radius of the centre queries
    std::vector<float> centre_distance_;  // m, per gate cell; < 0 = not yet known
    std::size_t resolved_ = 0;
};

}  // namespace peensim
