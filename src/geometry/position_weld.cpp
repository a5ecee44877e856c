#include "geometry/position_weld.h"

#include <cmath>
#include <stdexcept>

namespace peensim {

PositionWeld::PositionWeld(double tolerance) : tolerance_(tolerance) {
    if (!(tolerance > 0.0) || !std::isfinite(tolerance))
        throw std::invalid_argument("PositionWeld: the tolerance must be positive and finite");
}

std::size_t PositionWeld::CellHash::operator()(const Cell& cell) const {
    // Three large odd multipliers (as in spatial hashing of particles): neighbouring cells spread.
    const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
    return static_cast<std::size_t>(u(cell[0]) * 0x9E3779B97F4A7C15ULL ^ u(cell[1]) * 0xC2B2AE3D27D4EB4FULL ^
                                    u(cell[2]) * 0x165667B19E3779F9ULL);
}

PositionWeld::Cell PositionWeld::cell_of(const Vec3& position) const {
    return {static_cast<std::int64_t>(std::floor(position.x() / tolerance_)),
            static_cast<std::int64_t>(std::floor(position.y() / tolerance_)),
            static_cast<std::int64_t>(std::floor(position.z() / tolerance_))};
}

int PositionWeld::vertex(const Vec3& position) {
    const Cell home = cell_of(position);
    int found = -1;
    for (std::int64_t dx = -1; dx <= 1; ++dx)
        for (std::int64_t dy = -1; dy <= 1; ++dy)
            for (std::int64_t dz = -1; dz <= 1; ++dz) {
                const auto it = vertices_in_cell_.find({home[0] + dx, home[1] + dy, home[2] + dz});
                if (it == vertices_in_cell_.end()) continue;
                for (int v : it->second)
                    if ((vertices_[static_cast<std::size_t>(v)] - position).norm() <= tolerance_ && (found < 0 || v < found)) found = v;
            }
    if (found >= 0) return found;
    vertices_.push_back(position);
    const int index = static_cast<int>(vertices_.size() - 1);
    vertices_in_cell_[home].push_back(index);
    return index;
}

}  // namespace peensim
