// The triangles of one mesh near a point: a uniform grid of triangle centroids, built once, read
// without allocating. For laws that act on a patch of the surface around a contact (the
// impact-history law marks every triangle within one dent diameter of an impact).
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "common/vec.h"

namespace peensim::contact {

class FacetIndex {
public:
    // corners: three per triangle, in the frame the queries use (m). cell_m: the least grid spacing
    // (m, > 0); the grid is never finer than the largest triangle, so a query scans few cells.
    FacetIndex(std::vector<Vec3> corners, double cell_m);

    std::size_t triangle_count() const { return corners_.size() / 3; }

    // Calls visit(triangle) once for every triangle whose closest point to p is within radius_m.
    template <class Visit>
    void for_each_within(const Vec3& p, double radius_m, Visit&& visit) const;

private:
    using CellKey = std::uint64_t;
    CellKey key(long long ix, long long iy, long long iz) const;
    long long cell_of(double x) const;
    double distance_to(std::size_t triangle, const Vec3& p) const;

    std::vector<Vec3> corners_;                             // m
    double cell_m_ = 0.0;                                   // m
    double reach_m_ = 0.0;                                  // m, largest centroid-to-corner distance
    std::vector<std::pair<CellKey, std::uint32_t>> cells_;  // (cell of the centroid, triangle), sorted
};

template <class Visit>
void FacetIndex::for_each_within(const Vec3& p, double radius_m, Visit&& visit) const {
    // A triangle within radius of p has its centroid within radius + reach of p.
    const double r = radius_m + reach_m_;
    const long long x0 = cell_of(p.x() - r), x1 = cell_of(p.x() + r);
    const long long y0 = cell_of(p.y() - r), y1 = cell_of(p.y() + r);
    const long long z0 = cell_of(p.z() - r), z1 = cell_of(p.z() + r);
    // A query wider than the mesh has cells (a dent larger than the part): every triangle once.
    if (static_cast<double>(x1 - x0 + 1) * static_cast<double>(y1 - y0 + 1) * static_cast<double>(z1 - z0 + 1) >
        static_cast<double>(cells_.size())) {
        for (std::size_t t = 0; t < triangle_count(); ++t)
            if (distance_to(t, p) <= radius_m) visit(t);
        return;
    }
    for (long long ix = x0; ix <= x1; ++ix)
        for (long long iy = y0; iy <= y1; ++iy)
            for (long long iz = z0; iz <= z1; ++iz) {
                const CellKey k = key(ix, iy, iz);
                auto it = std::lower_bound(cells_.begin(), cells_.end(), std::pair<CellKey, std::uint32_t>{k, 0});
                for (; it != cells_.end() && it->first == k; ++it)
                    if (distance_to(it->second, p) <= radius_m) visit(static_cast<std::size_t>(it->second));
            }
}

}  // namespace peensim::contact
