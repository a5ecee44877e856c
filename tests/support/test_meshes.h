// Small meshes the tests build in memory.
#pragma once

#include "geometry/triangle_mesh.h"

namespace peensim::testing {

// A flat square [0, side]^2 in z = 0 (m), two triangles sharing the diagonal (0,0)-(side,side).
inline TriangleMesh square(double side_m) {
    TriangleMesh mesh;
    mesh.vertices = {Vec3(0, 0, 0), Vec3(side_m, 0, 0), Vec3(side_m, side_m, 0), Vec3(0, side_m, 0)};
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    mesh.source_facet = {0, 1};
    return mesh;
}

}  // namespace peensim::testing
