// Which points lie inside the closed chamber assembly, and whether it is closed at all.
// All components at t = 0 are voxelised together in the world frame (a DistanceGate over their
// union); the outside is flood-filled from the grid's border through cells a shot could pass
// (at least ~1.25 shot diameters of clearance), then grown by two cells into free space so that
// free cells hugging the outer walls count as outside too. Whatever free cell is not outside is
// inside. A gap narrower than ~1.25 D is therefore not reported here; a shot that still finds its
// way out during a run is caught and counted as lost by the engine.
#pragma once

#include <memory>
#include <vector>

#include "collision/distance_gate.h"
#include "common/vec.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

class Enclosure {
public:
    // world_mesh: every component's triangles in the world frame; cell_size_m ~ R / 2.
    Enclosure(const TriangleMesh& world_mesh, double cell_size_m, double shot_radius_m);

    // True if p (world, m) is in free space enclosed by the assembly.
    bool inside(const Vec3& p) const;

    // A point (world, m) on a path of free cells from p to the outside, just outside the box
    // [lo, hi] (typically the chamber's bounds): where the shot would leave. False if p is enclosed.
    bool escape_point(const Vec3& p, const Vec3& lo, const Vec3& hi, Vec3& where) const;

private:
    std::size_t index(int i, int j, int k) const {
        return (static_cast<std::size_t>(k) * static_cast<std::size_t>(grid_.ny()) + static_cast<std::size_t>(j)) *
                   static_cast<std::size_t>(grid_.nx()) + static_cast<std::size_t>(i);
    }
    bool passable(int i, int j, int k) const { return grid_.level(i, j, k) >= passable_level_; }

    DistanceGate grid_;
    int passable_level_ = 3;
    std::vector<unsigned char> outside_;
};

}  // namespace peensim
