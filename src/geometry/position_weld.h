// Welds points that lie within a tolerance of each other into one vertex: for surfaces stitched from
// pieces computed separately (each face of a CAD model is tessellated on its own), whose shared
// boundary points coincide in position but need not to the last bit. MeshBuilder welds exact
// positions only; this finds, for each new point, a vertex already kept within `tolerance` of it
// (the first one kept wins, so the result does not depend on anything but the order of the points).
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "common/vec.h"

namespace peensim {

class PositionWeld {
public:
    // tolerance: in the points' unit (> 0); points closer than it are one vertex. Keep it far below
    // the shortest edge of the surface and far above the coordinates' round-off.
    explicit PositionWeld(double tolerance);

    // Index of the vertex within the tolerance of `position`, adding it if there is none.
    int vertex(const Vec3& position);

    const std::vector<Vec3>& vertices() const { return vertices_; }

private:
    using Cell = std::array<std::int64_t, 3>;
    struct CellHash {
        std::size_t operator()(const Cell& cell) const;
    };

    Cell cell_of(const Vec3& position) const;

    double tolerance_;
    std::vector<Vec3> vertices_;
    // Vertices by the cube of edge `tolerance` they lie in; a point's match lies in its cube or a
    // neighbouring one.
    std::unordered_map<Cell, std::vector<int>, CellHash> vertices_in_cell_;
};

}  // namespace peensim
