// The mesh an impact map is drawn on (render/map_mesh.h): sub-triangles no longer than the
// spacing, covering the same area; a constant field stays that constant exactly; the faces either
// side of a sharp edge keep their own values (to rounding); no data stays no data; values between two
// neighbouring triangles are interpolated between them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geometry/box_mesh.h"
#include "render/map_mesh.h"

using namespace peensim;

namespace {

double area_of(const TriangleMesh& m, std::size_t t) {
    return 0.5 * (m.corner(t, 1) - m.corner(t, 0)).cross(m.corner(t, 2) - m.corner(t, 0)).norm();
}
Vec3 normal_of(const TriangleMesh& m, std::size_t t) {
    return (m.corner(t, 1) - m.corner(t, 0)).cross(m.corner(t, 2) - m.corner(t, 0)).normalized();
}

TriangleMesh cube() {
    BoxSpec spec;
    spec.size_m = Vec3(0.01, 0.01, 0.01);
    spec.divisions = Eigen::Vector3i(2, 2, 2);
    return box(spec);
}

}  // namespace

TEST(MapMesh, SubTrianglesAreNoLongerThanTheSpacingAndCoverTheSameArea) {
    const TriangleMesh mesh = cube();
    const std::vector<double> values(mesh.triangle_count(), 3.0);
    const MapMesh map = map_mesh(mesh, values, 1e-3);
    double area = 0.0, sub_area = 0.0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) area += area_of(mesh, t);
    for (std::size_t t = 0; t < map.mesh.triangle_count(); ++t) {
        sub_area += area_of(map.mesh, t);
        for (int k = 0; k < 3; ++k) EXPECT_LE((map.mesh.corner(t, (k + 1) % 3) - map.mesh.corner(t, k)).norm(), 1e-3 * (1 + 1e-12));
        EXPECT_NEAR(map.values[t], 3.0, 1e-14);  // a constant field (to rounding)
    }
    EXPECT_NEAR(sub_area, area, 1e-12 * area);
    // 5 mm squares cut in two: the diagonal 7.07 mm -> 8 parts per edge, 64 sub-triangles each.
    EXPECT_EQ(map.mesh.triangle_count(), 64 * mesh.triangle_count());
    EXPECT_THROW(map_mesh(mesh, std::vector<double>(3, 0.0), 1e-3), std::invalid_argument);
    EXPECT_THROW(map_mesh(mesh, values, 0.0), std::invalid_argument);
}

TEST(MapMesh, SharpEdgesKeepTheirSidesAndNoDataStaysNoData) {
    const TriangleMesh mesh = cube();
    std::vector<double> values(mesh.triangle_count());
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const Vec3 n = normal_of(mesh, t);
        values[t] = n.z() > 0.9 ? 1.0 : (n.z() < -0.9 ? std::numeric_limits<double>::quiet_NaN() : 0.0);
    }
    const MapMesh map = map_mesh(mesh, values, 1e-3);
    for (std::size_t t = 0; t < map.mesh.triangle_count(); ++t) {
        const Vec3 n = normal_of(map.mesh, t);
        if (n.z() > 0.9) {
            EXPECT_NEAR(map.values[t], 1.0, 1e-14);
        } else if (n.z() < -0.9) {
            EXPECT_TRUE(std::isnan(map.values[t]));
        } else {
            EXPECT_NEAR(map.values[t], 0.0, 1e-14);
        }
    }
}

TEST(MapMesh, ValuesAreInterpolatedBetweenNeighbours) {
    // The top face of the cube: its 8 triangles 0 where x < 0, 1 where x > 0. Across the middle
    // the map goes from 0 to 1 through values in between, never outside [0, 1].
    const TriangleMesh mesh = cube();
    std::vector<double> values(mesh.triangle_count(), 0.0);
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const Vec3 c = (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0;
        if (normal_of(mesh, t).z() > 0.9 && c.x() > 0.0) values[t] = 1.0;
    }
    const MapMesh map = map_mesh(mesh, values, 0.5e-3);
    int between = 0;
    for (std::size_t t = 0; t < map.mesh.triangle_count(); ++t) {
        if (normal_of(map.mesh, t).z() < 0.9) continue;
        EXPECT_GE(map.values[t], 0.0);
        EXPECT_LE(map.values[t], 1.0);
        const double x = (map.mesh.corner(t, 0) + map.mesh.corner(t, 1) + map.mesh.corner(t, 2)).x() / 3.0;
        if (std::abs(x) < 1e-3) between += map.values[t] > 0.05 && map.values[t] < 0.95;
        if (x < -4.5e-3) {
            EXPECT_LT(map.values[t], 0.2) << x;
        }
        if (x > 4.5e-3) {
            EXPECT_GT(map.values[t], 0.8) << x;
        }
    }
    EXPECT_GT(between, 10);
}
