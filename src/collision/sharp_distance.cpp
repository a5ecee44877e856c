#include "collision/sharp_distance.h"

#include <cmath>

namespace peensim {

SharpDistance::SharpDistance(const DistanceGate& gate, const MeshCollider& collider, double reach_m)
    : gate_(&gate),
      collider_(&collider),
      reach_(reach_m),
      resolve_(reach_m + gate.half_diagonal()),
      centre_distance_(gate.cell_count(), -1.0f) {}

float SharpDistance::exact_distance(const Vec3& centre) {
    ++resolved_;
    MeshCollider::Closest closest;
    MeshCollider::QueryCounters counters;
    if (!collider_->closest_within(centre, resolve_, closest, counters)) return std::nextafter(static_cast<float>(resolve_), 0.0f);
    // Rounded down to float so the bound stays a lower bound.
    return std::nextafter(static_cast<float>(closest.distance), 0.0f);
}

}  // namespace peensim
