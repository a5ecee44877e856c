// Hexahedral meshes for the FEM hand-off (`peensim export-fem`): nodes in metres and 8-node
// bricks in the node order of Abaqus' and CalculiX's C3D8 (nodes 1-4 one face counter-clockwise
// seen from inside-out of the opposite face 5-8, so that the volume is positive). Face numbers
// follow the same convention: S1 = 1-2-3-4, S2 = 5-8-7-6, S3 = 1-5-6-2, S4 = 2-6-7-3,
// S5 = 3-7-8-4, S6 = 4-8-5-1.
#pragma once

#include <array>
#include <vector>

#include "common/vec.h"

namespace peensim {

using HexElement = std::array<int, 8>;  // 0-based indices into HexMesh::nodes

struct HexFace {
    int element = 0;  // 0-based index into HexMesh::elements
    int face = 1;     // 1..6 (S1..S6)
};

struct HexMesh {
    std::vector<Vec3> nodes;  // m
    std::vector<HexElement> elements;
};

// The element built on the grid cell (i, j, k) of a structured grid whose node (i, j, k) is
// node_index(i, j, k): corners in C3D8 order (z lower face first), positive volume when i, j, k
// run along a right-handed frame.
template <class NodeIndex>
HexElement grid_cell(int i, int j, int k, NodeIndex node_index) {
    return {node_index(i, j, k),     node_index(i + 1, j, k),     node_index(i + 1, j + 1, k),     node_index(i, j + 1, k),
            node_index(i, j, k + 1), node_index(i + 1, j, k + 1), node_index(i + 1, j + 1, k + 1), node_index(i, j + 1, k + 1)};
}

// Signed volume of a brick (m^3), by its decomposition into 6 tetrahedra along the 1-7 diagonal.
inline double hex_volume(const HexMesh& mesh, const HexElement& e) {
    auto p = [&](int a) -> const Vec3& { return mesh.nodes[static_cast<std::size_t>(e[static_cast<std::size_t>(a)])]; };
    auto tet = [&](int a, int b, int c, int d) { return (p(b) - p(a)).cross(p(c) - p(a)).dot(p(d) - p(a)) / 6.0; };
    return tet(0, 1, 2, 6) + tet(0, 2, 3, 6) + tet(0, 3, 7, 6) + tet(0, 7, 4, 6) + tet(0, 4, 5, 6) + tet(0, 5, 1, 6);
}

}  // namespace peensim
