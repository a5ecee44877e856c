// Which cells of a uniform grid over one mesh a triangle may pass through, and, in O(1) for a box
// of any size, whether any such cell overlaps the box: a summed-volume table (3D prefix sums) of
// the marked cells. MeshCollider::first_hit asks it before walking its BVH: a search window whose
// swept sphere's bounds meet no marked cell can touch no triangle, and is a miss without the walk.
//
// Why: most of an event-driven run's search windows lie in the open cavity of a chamber, where the
// BVH cannot end its walk at the root. A closed chamber's root box, and the boxes of its halves
// and quarters, hold every point of the cavity, so the walk descends a dozen levels, each node's
// swept-sphere span a few quadratics, before every box is out of reach (on the shipped gear, 23
// nodes and ~4200 cycles a window that finds nothing: half of the run's mesh queries).
//
// Conservative by construction: a cell is marked when its centre lies within half its diagonal
// (with a relative slack for rounding) of a triangle, which every cell the triangle meets does;
// a box's cells are those its corners fall in, each floor widened by a margin. So a point of a
// triangle inside the box lies in a marked cell the query counts, and "no marked cell" is exact.
#pragma once

#include <cstdint>
#include <vector>

#include "common/vec.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

class OccupiedCells {
public:
    // A grid over the mesh's bounds with at most about max_cells cells (cubic cells; a flat or
    // thin mesh gets its cells from its larger extents).
    explicit OccupiedCells(const TriangleMesh& mesh, double max_cells = kDefaultCells);

    // True if some marked cell overlaps the box [lo, hi] (m, mesh frame); false only if no
    // triangle has a point inside it. Non-finite bounds: true (nothing is ruled out).
    bool any_in(const Vec3& lo, const Vec3& hi) const;

    double cell_size() const { return cell_; }                  // m
    std::size_t marked() const { return marked_; }              // cells a triangle may meet
    std::size_t cell_count() const { return nx_ * ny_ * nz_; }  // cells of the grid
    std::size_t memory_bytes() const { return sums_.size() * sizeof(std::uint32_t); }

    // About 1 MB of sums per mesh: cells of ~2.3 mm in the shipped gear's chamber. A million
    // cells (4 MB a mesh) answered no more sweeps there and took 13 MB more of the gear's run.
    static constexpr double kDefaultCells = 2.5e5;

private:
    // The number of marked cells (i', j', k') with i' < i, j' < j, k' < k.
    std::uint32_t sum(std::size_t i, std::size_t j, std::size_t k) const { return sums_[(k * (ny_ + 1) + j) * (nx_ + 1) + i]; }

    Vec3 origin_ = Vec3::Zero();  // m, the grid's lower corner
    double cell_ = 1.0;           // m
    double inv_cell_ = 1.0;       // 1/m
    std::size_t nx_ = 0, ny_ = 0, nz_ = 0;
    std::size_t marked_ = 0;
    std::vector<std::uint32_t> sums_;  // (nx + 1)(ny + 1)(nz + 1), zero on the lower faces
};

}  // namespace peensim
