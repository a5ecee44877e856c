// The generalised winding number (geometry/winding_number.h): exact values about a closed box,
// which the nozzle checks use to tell an exit inside a part.
#include <gtest/gtest.h>

#include "geometry/box_mesh.h"
#include "geometry/winding_number.h"

namespace peensim {
namespace {

TriangleMesh unit_box() {
    BoxSpec spec;
    spec.size_m = Vec3(0.02, 0.01, 0.015);
    spec.divisions = Eigen::Vector3i(3, 2, 2);
    return box(spec);  // centred on the origin, normals outward
}

TEST(WindingNumber, OneInsideAClosedMeshZeroOutside) {
    const TriangleMesh mesh = unit_box();
    EXPECT_NEAR(winding_number(mesh, Vec3(0.0, 0.0, 0.0)), 1.0, 1e-12);
    EXPECT_NEAR(winding_number(mesh, Vec3(0.0099, 0.0049, -0.0074)), 1.0, 1e-9);  // near a corner, inside
    EXPECT_NEAR(winding_number(mesh, Vec3(0.0101, 0.0, 0.0)), 0.0, 1e-9);         // just outside a face
    EXPECT_NEAR(winding_number(mesh, Vec3(1.0, 2.0, 3.0)), 0.0, 1e-12);
    EXPECT_NEAR(winding_number(mesh, Vec3(0.001, 0.0013, 0.0074999)), 1.0, 1e-6);  // a tenth of a um under the top face
    EXPECT_NEAR(winding_number(mesh, Vec3(0.001, 0.0013, 0.0075001)), 0.0, 1e-6);  // and over it
}

TEST(WindingNumber, InsideOutWindingCountsMinusOne) {
    TriangleMesh mesh = unit_box();
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    EXPECT_NEAR(winding_number(mesh, Vec3(0.001, 0.002, 0.003)), -1.0, 1e-12);
}

}  // namespace
}  // namespace peensim
