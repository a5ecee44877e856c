// Which points lie inside the closed chamber assembly, and whether it is closed at all.
// All components at t = 0 are voxelised together in the world frame (a DistanceGate over their
// union); the outside is flood-filled from the grid's border through cells a shot could pass
// (at least ~1.25 shot diameters of clearance), then grown by two cells into free space so that
// free cells hugging the outer walls count as outside too. Whatever free cell is not outside is
// inside. A gap narrower than ~1.25 D is therefore not reported here; a shot that still finds its
// way out during a run is caught and counted as lost by the engine.
// The inside falls into regions: free cells joined face to face. The chamber's cavity is one; the
// inside of a closed part (a rod, a blade) or a sealed pocket is another, cut off from it by the
// cells its surface touches. Shot are placed only in the cavity above the sonotrode.
// Cells are half a shot radius (the requested size), coarser where that would take more than ~8 M
// cells (small shot in a large assembly: 0.3 mm shot in the rod chamber took 356 M cells, 3.5 s
// and 0.5 GB). In a coarse grid (cells wider than a shot) a gap a few shot wide may lie all in
// cells the walls touch: the 15 mm gap over a 1 m cube under the chamber's lid (cells of 6.5 mm),
// whose top face then read as out of every shot's reach (16.7 % of the part), or the 20 mm gap
// under a 1.5 m cube over the sonotrode, read as a leak at the very point probed. So there a
// touched cell whose centre is clear of every surface by a shot radius is free too, and two
// neighbours of which one is such a cell are joined only where the straight path between their
// centres is clear by a shot radius (checked exactly). A shot centre hugging a wall then lies in a
// cell the wall touches, which says nothing of its side: such a point is read from the nearest
// free cell it sees along a straight path clear of every surface (checked exactly, by the caller's
// clearance function), so the answer for a given point does not depend on the grid.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <vector>

#include "collision/distance_gate.h"
#include "common/vec.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

class Enclosure {
public:
    // Exact distance (m) from p (world, m) to the nearest surface of the assembly, or `within` (m)
    // if none is closer.
    using Clearance = std::function<double(const Vec3& p, double within)>;

    // world_mesh: every component's triangles in the world frame; cell_size_m: the finest cells
    // wanted (m, ~R / 2).
    Enclosure(const TriangleMesh& world_mesh, double cell_size_m, double shot_radius_m, Clearance clearance);

    // True if p (world, m) is in free space enclosed by the assembly.
    bool inside(const Vec3& p) const;
    // True if the grid can read p (world, m): a free cell holds it or it sees one (probe_cell). A
    // point it cannot read (in a pocket finer than the cells) is neither inside nor outside.
    bool reads(const Vec3& p) const;

    // The enclosed region p (world, m) lies in (a number >= 0, the same for every point of the
    // region), or -1 if p is not inside. A region is numbered (flood-filled) when first asked for.
    int region(const Vec3& p);
    // Whether p lies in region `number` (region()'s), which must have been numbered already: a
    // query that numbers nothing, so safe from several threads at once.
    bool in_region(const Vec3& p, int number) const;

    double cell_size() const { return grid_.cell_size(); }
    // How many touched cells of a coarse grid are free at their centre (0 in a fine grid).
    std::size_t free_centres() const { return free_centres_; }

    // A point (world, m) on a path of free cells from p to the outside, just outside the box
    // [lo, hi] (typically the chamber's bounds): where the shot would leave. False if p is
    // enclosed, or if the grid cannot read it (reads()).
    bool escape_point(const Vec3& p, const Vec3& lo, const Vec3& hi, Vec3& where) const;

private:
    std::size_t index(int i, int j, int k) const {
        return (static_cast<std::size_t>(k) * static_cast<std::size_t>(grid_.ny()) + static_cast<std::size_t>(j)) *
                   static_cast<std::size_t>(grid_.nx()) +
               static_cast<std::size_t>(i);
    }
    bool passable(int i, int j, int k) const { return grid_.level(i, j, k) >= passable_level_; }
    // Free: untouched by any surface (level > 0), or touched with its centre clear (a coarse grid).
    bool free_cell(int i, int j, int k) const {
        return grid_.level(i, j, k) > 0 || (!centre_clearance_.empty() && centre_clearance_[index(i, j, k)] >= free_clearance_);
    }
    // Whether a shot centre passes between the centres of the face neighbours a and b, both free:
    // always between untouched cells (as in a fine grid); else where the straight path is clear
    // by a shot radius.
    bool joined(const std::array<int, 3>& a, const std::array<int, 3>& b) const;
    // Whether the straight path between the centres of the face neighbours a and b is clear of
    // every surface by a shot radius (a Lipschitz bound from their centres' clearance, else traced).
    bool passes(const std::array<int, 3>& a, const std::array<int, 3>& b) const;
    // m, a lower bound of the clearance of cell (i, j, k)'s centre (an untouched cell's: half its diagonal).
    double centre_clearance(int i, int j, int k) const;
    // The free cell p is read from: its own, or the nearest free one within two cells that a
    // straight path clear of every surface joins to it. False if none (or p off the grid).
    bool probe_cell(const Vec3& p, int& i, int& j, int& k) const;
    // Whether every point of the segment ab lies farther than r (m) from every surface (r = 0:
    // clear of them), by sphere tracing.
    bool segment_clear(const Vec3& a, const Vec3& b, double r = 0.0) const;
    bool inside_cell(int i, int j, int k) const { return free_cell(i, j, k) && label_[index(i, j, k)] != kOutside; }

    // Per cell: kOutside, kUnnumbered (inside, or a surface cell), or a region's number + kFirstRegion.
    static constexpr unsigned char kUnnumbered = 0, kOutside = 1, kFirstRegion = 2;
    // Regions past the last number a byte holds share it (the chamber's cavity is numbered first).
    static constexpr unsigned char kLastRegion = 255;

    DistanceGate grid_;
    Clearance clearance_;
    double shot_radius_ = 0.0;  // m
    int passable_level_ = 3;
    // A coarse grid's touched cells: their centre's clearance (m, float, rounded down; -1 where
    // unknown); empty in a fine grid, where no touched cell's centre can hold a shot.
    std::vector<float> centre_clearance_;
    float free_clearance_ = 0.0f;  // m, a centre at least this clear holds a shot
    std::size_t free_centres_ = 0;
    std::vector<unsigned char> label_;
    unsigned char next_region_ = kFirstRegion;
};

}  // namespace peensim
