// Neighbour search of the event-driven scheme: every shot owns one box that holds its sphere for
// as long as its current flight is known (from its last event to its next), kept in Bullet's
// dynamic AABB tree (btDbvt, the tree btDbvtBroadphase is made of, used directly so that boxes
// are stored exactly, without the broad phase's velocity margins). A shot predicting its next
// collision asks which boxes overlap its own: only those shot can meet it before either flight
// changes. Boxes are in metres; queries allocate nothing once the result vector is warm.
#pragma once

#include <memory>
#include <vector>

#include "common/vec.h"

namespace peensim {

class ShotBoxTree {
public:
    explicit ShotBoxTree(int shot_count);
    ~ShotBoxTree();
    ShotBoxTree(const ShotBoxTree&) = delete;
    ShotBoxTree& operator=(const ShotBoxTree&) = delete;

    // Sets shot i's box (m, world); inserts it if it has none.
    void set(int shot, const Vec3& lo, const Vec3& hi);
    // Room for shot_count shot (never fewer), the new ones without a box.
    void grow(int shot_count);
    // Takes shot i out (a lost shot).
    void remove(int shot);
    // The shots whose boxes overlap [lo, hi] (m), into `out` (cleared first), in no set order.
    void overlapping(const Vec3& lo, const Vec3& hi, std::vector<int>& out) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace peensim
