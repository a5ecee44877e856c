#include "contact/facet_index.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "kernels/closest_point.h"

namespace peensim::contact {

namespace {
// Cells per axis are wrapped into 21 bits each: cells that share a key are merely searched
// together (the distance test decides), so a wrap costs time, never a wrong answer.
constexpr std::uint64_t kAxisBits = 21;
constexpr std::uint64_t kAxisMask = (std::uint64_t{1} << kAxisBits) - 1;
}  // namespace

FacetIndex::FacetIndex(std::vector<Vec3> corners, double cell_m) : corners_(std::move(corners)), cell_m_(cell_m) {
    if (!(cell_m > 0.0) || corners_.size() % 3 != 0) throw std::invalid_argument("FacetIndex: a positive cell and whole triangles");
    const std::size_t n = triangle_count();
    const auto centroid = [&](std::size_t t) { return Vec3((corners_[3 * t] + corners_[3 * t + 1] + corners_[3 * t + 2]) / 3.0); };
    for (std::size_t t = 0; t < n; ++t)
        for (std::size_t k = 0; k < 3; ++k) reach_m_ = std::max(reach_m_, (corners_[3 * t + k] - centroid(t)).norm());
    cell_m_ = std::max(cell_m_, reach_m_);
    cells_.reserve(n);
    for (std::size_t t = 0; t < n; ++t) {
        const Vec3 c = centroid(t);
        cells_.emplace_back(key(cell_of(c.x()), cell_of(c.y()), cell_of(c.z())), static_cast<std::uint32_t>(t));
    }
    std::sort(cells_.begin(), cells_.end());
}

FacetIndex::CellKey FacetIndex::key(long long ix, long long iy, long long iz) const {
    const auto wrap = [](long long i) { return static_cast<std::uint64_t>(i) & kAxisMask; };
    return wrap(ix) | (wrap(iy) << kAxisBits) | (wrap(iz) << (2 * kAxisBits));
}

long long FacetIndex::cell_of(double x) const { return static_cast<long long>(std::floor(x / cell_m_)); }

double FacetIndex::distance_to(std::size_t t, const Vec3& p) const {
    return (closest_point_on_triangle(p, corners_[3 * t], corners_[3 * t + 1], corners_[3 * t + 2]).point - p).norm();
}

}  // namespace peensim::contact
