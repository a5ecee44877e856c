// A coarse voxel grid over one mesh, in the mesh's own frame, that answers in O(1) a lower
// bound of the distance from a point to the mesh. The engine asks it before every BVH query
// and skips the query when the shot cannot touch the mesh: this keeps the cost of a step flat
// in the triangle count (a fine part costs only for the few shots near it).
//
// How: cells that any triangle may touch are marked (cell centre within half a cell diagonal of
// the triangle: a superset of the cells the triangle crosses, so the bound stays conservative);
// a separable distance transform (axis by axis) stores the Chebyshev cell distance k to the nearest
// marked cell. Two cells k apart are at least (k - 1) cells apart along some axis, so
// distance >= (k - 1) * cell_size.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "common/vec.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

class DistanceGate {
public:
    // cell_size_m: grid spacing (m); reach_m: distances beyond this need not be resolved (m);
    // max_cells: a grid that would have more is coarsened by 25 % steps until it fits (a lower
    // bound still, less sharp). The default, 400 MB of levels, guards memory.
    DistanceGate(const TriangleMesh& mesh, double cell_size_m, double reach_m, double max_cells = 4e8);

    // The gate time stepping uses for a component's mesh: cells of half a shot radius (coarser
    // for large meshes, at most ~8 M cells), resolving distances up to a diameter plus `swing`
    // (m, how far the surface moves: twice a sonotrode's amplitude).
    static DistanceGate for_shot(const TriangleMesh& mesh, double shot_radius_m, double swing_m);

    // The finest cell size (m) at or above finest_m whose grid over the mesh's bounds grown by
    // margin_m on every side has at most max_cells cells: fine meshes and small shot in a large
    // assembly coarsen the grid instead of exhausting memory.
    static double cell_within(const TriangleMesh& mesh, double finest_m, double margin_m, double max_cells);

    // Lower bound (m) of the distance from p (mesh frame) to the mesh.
    double lower_bound(const Vec3& p) const {
        const Vec3 q = (p - origin_) * inv_cell_;
        const double fx = q.x(), fy = q.y(), fz = q.z();
        if (fx < 0.0 || fy < 0.0 || fz < 0.0 || fx >= nx_ || fy >= ny_ || fz >= nz_) return outside_bound(p);
        const std::size_t i = static_cast<std::size_t>(fx), j = static_cast<std::size_t>(fy), k = static_cast<std::size_t>(fz);
        return bound_of_level_[cells_[(k * static_cast<std::size_t>(ny_) + j) * static_cast<std::size_t>(nx_) + i]];
    }

    // Grid access, for whole-grid passes (enclosure flood fill).
    int nx() const { return nx_; }
    int ny() const { return ny_; }
    int nz() const { return nz_; }
    // Chebyshev cell distance of cell (i, j, k) to the nearest cell a triangle may touch (0 = touched).
    int level(int i, int j, int k) const {
        return cells_[(static_cast<std::size_t>(k) * static_cast<std::size_t>(ny_) + static_cast<std::size_t>(j)) *
                          static_cast<std::size_t>(nx_) +
                      static_cast<std::size_t>(i)];
    }
    Vec3 cell_centre(int i, int j, int k) const { return origin_ + cell_ * Vec3(i + 0.5, j + 0.5, k + 0.5); }
    // Cell containing p, or false if p is outside the grid.
    bool cell_of(const Vec3& p, int& i, int& j, int& k) const {
        const Vec3 q = (p - origin_) * inv_cell_;
        if (q.x() < 0.0 || q.y() < 0.0 || q.z() < 0.0 || q.x() >= nx_ || q.y() >= ny_ || q.z() >= nz_) return false;
        i = static_cast<int>(q.x()), j = static_cast<int>(q.y()), k = static_cast<int>(q.z());
        return true;
    }

    std::size_t cell_index(int i, int j, int k) const {
        return (static_cast<std::size_t>(k) * static_cast<std::size_t>(ny_) + static_cast<std::size_t>(j)) * static_cast<std::size_t>(nx_) +
               static_cast<std::size_t>(i);
    }
    double half_diagonal() const { return 0.5 * std::sqrt(3.0) * cell_; }

    double cell_size() const { return cell_; }
    std::size_t cell_count() const { return cells_.size(); }
    std::size_t memory_bytes() const { return cells_.size() * sizeof(std::uint8_t); }

private:
    double outside_bound(const Vec3& p) const;
    // cells_: 0 where marked, `levels` elsewhere -> the Chebyshev distance in cells to the nearest
    // marked cell, capped at `levels`.
    void chebyshev_transform(int levels);

    Vec3 origin_;            // m, corner of cell (0,0,0)
    double cell_ = 0.0;      // m
    double inv_cell_ = 0.0;  // 1/m
    int nx_ = 0, ny_ = 0, nz_ = 0;
    Vec3 mesh_lo_, mesh_hi_;              // m, mesh bounds
    std::vector<std::uint8_t> cells_;     // Chebyshev cell distance to a marked cell, capped
    std::vector<double> bound_of_level_;  // m, lower bound for each stored level
};

}  // namespace peensim
