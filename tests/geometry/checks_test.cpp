// Mesh measurements (area, divergence volume, edge topology, bounds) on hand-built meshes
// whose answers are known exactly, and the exact-position welding of MeshBuilder.
#include <gtest/gtest.h>

#include "geometry/mesh_builder.h"
#include "geometry/mesh_checks.h"

namespace peensim {
namespace {

// Axis-aligned box [0, a] x [0, b] x [0, c] from 8 corners and 12 outward triangles.
TriangleMesh hand_box(double a, double b, double c, Vec3 offset = Vec3::Zero()) {
    TriangleMesh m;
    for (int k = 0; k < 8; ++k) m.vertices.push_back(offset + Vec3((k & 1) ? a : 0.0, (k & 2) ? b : 0.0, (k & 4) ? c : 0.0));
    m.triangles = {{0, 2, 1}, {1, 2, 3},   // z = 0, normal -z
                   {4, 5, 6}, {5, 7, 6},   // z = c, normal +z
                   {0, 1, 4}, {1, 5, 4},   // y = 0, normal -y
                   {2, 6, 3}, {3, 6, 7},   // y = b, normal +y
                   {0, 4, 2}, {2, 4, 6},   // x = 0, normal -x
                   {1, 3, 5}, {3, 7, 5}};  // x = a, normal +x
    for (int t = 0; t < 12; ++t) {
        m.source_facet.push_back(t);
        m.group_of_triangle.push_back(0);
    }
    m.group_names = {""};
    return m;
}

TEST(GeometryChecks, BoxAreaVolumeAndBounds) {
    const TriangleMesh m = hand_box(2.0, 3.0, 5.0);
    EXPECT_DOUBLE_EQ(surface_area(m), 2.0 * (6.0 + 15.0 + 10.0));
    EXPECT_DOUBLE_EQ(enclosed_volume(m), 30.0);
    const Bounds b = bounds(m);
    EXPECT_EQ(b.min_m, Vec3(0, 0, 0));
    EXPECT_EQ(b.max_m, Vec3(2, 3, 5));
    EXPECT_EQ(b.size_m(), Vec3(2, 3, 5));
}

TEST(GeometryChecks, VolumeIsAccurateFarFromTheOrigin) {
    const TriangleMesh m = hand_box(1e-3, 1e-3, 1e-3, Vec3(1e3, -2e3, 5e2));
    EXPECT_NEAR(enclosed_volume(m), 1e-9, 1e-9 * 1e-6);
}

TEST(GeometryChecks, NormalsFollowTheWinding) {
    const TriangleMesh m = hand_box(1.0, 1.0, 1.0);
    EXPECT_TRUE(triangle_normal(m, 0).isApprox(Vec3(0, 0, -1)));
    EXPECT_TRUE(triangle_normal(m, 2).isApprox(Vec3(0, 0, 1)));
    EXPECT_TRUE(triangle_normal(m, 11).isApprox(Vec3(1, 0, 0)));
    EXPECT_DOUBLE_EQ(triangle_area(m, 5), 0.5);
}

TEST(GeometryChecks, DegenerateTriangleHasZeroNormalAndArea) {
    TriangleMesh m;
    m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
    m.triangles = {{0, 1, 2}};
    EXPECT_EQ(triangle_normal(m, 0), Vec3::Zero());
    EXPECT_EQ(triangle_area(m, 0), 0.0);
}

TEST(GeometryChecks, ClosedBoxHasEveryEdgeTwice) {
    const TriangleMesh m = hand_box(1.0, 1.0, 1.0);
    const EdgeReport r = edge_report(m);
    EXPECT_EQ(r.edges, 18u);  // 12 box edges + 6 face diagonals
    EXPECT_EQ(r.boundary_edges, 0u);
    EXPECT_EQ(r.non_manifold_edges, 0u);
    EXPECT_EQ(r.misoriented_edges, 0u);
    EXPECT_TRUE(is_closed(m));
}

TEST(GeometryChecks, MissingTriangleLeavesAHole) {
    TriangleMesh m = hand_box(1.0, 1.0, 1.0);
    m.triangles.pop_back();
    const EdgeReport r = edge_report(m);
    EXPECT_EQ(r.boundary_edges, 3u);
    EXPECT_FALSE(is_closed(m));
}

TEST(GeometryChecks, FlippedTriangleIsMisorientedAndInvertedBoxHasNegativeVolume) {
    TriangleMesh m = hand_box(1.0, 1.0, 1.0);
    std::swap(m.triangles[0][1], m.triangles[0][2]);
    EXPECT_EQ(edge_report(m).misoriented_edges, 3u);
    EXPECT_TRUE(is_closed(m));  // still watertight

    TriangleMesh inverted = hand_box(1.0, 2.0, 3.0);
    for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
    EXPECT_DOUBLE_EQ(enclosed_volume(inverted), -6.0);
    EXPECT_EQ(edge_report(inverted).misoriented_edges, 0u);
}

TEST(GeometryChecks, FinCountsAsNonManifold) {
    TriangleMesh m = hand_box(1.0, 1.0, 1.0);
    m.vertices.push_back(Vec3(0.5, -1.0, 0.0));
    m.triangles.push_back({0, 1, 8});  // a third triangle on edge 0-1
    const EdgeReport r = edge_report(m);
    EXPECT_EQ(r.non_manifold_edges, 1u);
    EXPECT_EQ(r.boundary_edges, 2u);
    EXPECT_FALSE(is_closed(m));
}

TEST(GeometryChecks, EmptyMeshIsNotClosed) {
    const TriangleMesh m;
    EXPECT_FALSE(is_closed(m));
    EXPECT_EQ(enclosed_volume(m), 0.0);
    EXPECT_EQ(bounds(m).size_m(), Vec3::Zero());
}

TEST(GeometryMeshBuilder, WeldsExactlyEqualPositionsOnly) {
    MeshBuilder b;
    const int g = b.group("plate");
    b.add_quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), g);
    EXPECT_EQ(b.mesh().vertices.size(), 4u);        // the diagonal's two ends are shared
    EXPECT_EQ(b.vertex(Vec3(-0.0, 0.0, -0.0)), 0);  // -0 welds with +0
    EXPECT_EQ(b.vertex(Vec3(1e-300, 0, 0)), 4);     // any other value is a new vertex
    EXPECT_EQ(b.group("plate"), g);
    EXPECT_EQ(b.group("other"), 1);
    const TriangleMesh m = b.take();
    EXPECT_EQ(m.triangle_count(), 2u);
    EXPECT_EQ(m.source_facet, (std::vector<int>{0, 1}));
    EXPECT_EQ(m.group_of_triangle, (std::vector<int>{0, 0}));
    EXPECT_EQ(m.group_names, (std::vector<std::string>{"plate", "other"}));
    EXPECT_TRUE(triangle_normal(m, 0).isApprox(Vec3(0, 0, 1)));
    EXPECT_TRUE(triangle_normal(m, 1).isApprox(Vec3(0, 0, 1)));
    EXPECT_EQ(b.triangle_count(), 0u);  // take() empties the builder
}

}  // namespace
}  // namespace peensim
