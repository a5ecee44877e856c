// Per-triangle impact fields: counts, speeds and energy per area credited to the right triangle.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/triangle_fields.h"

using namespace peensim;

namespace {

// A unit square (1 m x 1 m) in z = 0 as one quad facet fanned into two triangles, and a second
// facet: a triangle of area 0.5 m2 beside it.
TriangleMesh square_and_triangle() {
    TriangleMesh m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}};
    m.source_facet = {0, 0, 1};
    m.group_names = {""};
    m.group_of_triangle = {0, 0, 0};
    return m;
}

}  // namespace

TEST(TriangleFields, CountsSpeedsAndEnergyPerTriangle) {
    const TriangleMesh mesh = square_and_triangle();
    const double mass = 3.2e-5;  // kg, a 2 mm steel shot
    TriangleFields f(mesh, mass);
    // Facet 0 is a quad: the point (0.8, 0.2) lies in triangle 0, (0.2, 0.8) in triangle 1.
    EXPECT_EQ(f.add(0, Vec3(0.8, 0.2, 0.0), 2.0), 0);
    EXPECT_EQ(f.add(0, Vec3(0.8, 0.1, 0.0), 4.0), 0);
    EXPECT_EQ(f.add(0, Vec3(0.2, 0.8, 0.0), 1.0), 1);
    EXPECT_EQ(f.add(1, Vec3(1.2, 0.3, 0.0), 3.0), 2);
    EXPECT_EQ(f.add(7, Vec3(0, 0, 0), 3.0), -1);  // a facet the mesh does not have
    EXPECT_EQ(f.unknown_facets(), 1u);

    EXPECT_EQ(f.count(0), 2u);
    EXPECT_DOUBLE_EQ(f.mean_normal_speed(0), 3.0);
    EXPECT_DOUBLE_EQ(f.max_normal_speed(0), 4.0);
    EXPECT_DOUBLE_EQ(f.area_m2(0), 0.5);
    // (1/2 m 2^2 + 1/2 m 4^2) / 0.5 m2 = 20 m J/m2.
    EXPECT_DOUBLE_EQ(f.energy_per_area(0), 20.0 * mass);
    // 2 impacts on 0.5 m2 = 5e5 mm2 over 2 s.
    EXPECT_DOUBLE_EQ(f.rate_per_mm2_s(0, 2.0), 2.0 / 5e5 / 2.0);
    EXPECT_EQ(f.count(1), 1u);
    EXPECT_EQ(f.count(2), 1u);
    EXPECT_TRUE(std::isnan(TriangleFields(mesh, mass).mean_normal_speed(0)));
}
