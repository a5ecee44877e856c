// Thinning a mesh for display (geometry/vertex_clustering.h): a coarse mesh is kept as it is; a
// fine one keeps at most the triangles asked for, each from a distinct triangle of the mesh, with
// about its area and its triangles' orientation.
#include <gtest/gtest.h>

#include <set>

#include "geometry/cylinder_mesh.h"
#include "geometry/vertex_clustering.h"

namespace peensim {
namespace vertex_clustering_cases {

double area_of(const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& tris) {
    double a = 0.0;
    for (const auto& t : tris)
        a += 0.5 * (v[static_cast<std::size_t>(t[1])] - v[static_cast<std::size_t>(t[0])])
                       .cross(v[static_cast<std::size_t>(t[2])] - v[static_cast<std::size_t>(t[0])])
                       .norm();
    return a;
}

TEST(VertexClustering, ACoarseMeshIsKeptAsItIs) {
    const TriangleMesh mesh = cylinder(CylinderSpec{5e-3, 20e-3, 32, Axis::z, Vec3::Zero(), true, 4, 2});
    const ThinnedMesh shown = thin_for_display(mesh, mesh.triangle_count());
    EXPECT_EQ(shown.cell_m, 0.0);
    ASSERT_EQ(shown.triangles.size(), mesh.triangle_count());
    for (std::size_t t = 0; t < shown.source.size(); ++t) EXPECT_EQ(shown.source[t], t);
}

TEST(VertexClustering, AFineMeshIsThinnedToTheCountAskedForWithItsAreaAndOrientation) {
    const TriangleMesh mesh = cylinder(CylinderSpec{5e-3, 20e-3, 400, Axis::z, Vec3::Zero(), true, 60, 20});
    const std::size_t max = 4000;
    ASSERT_GT(mesh.triangle_count(), 10 * max);
    const ThinnedMesh shown = thin_for_display(mesh, max);
    EXPECT_GT(shown.cell_m, 0.0);
    EXPECT_LE(shown.triangles.size(), max);
    EXPECT_GT(shown.triangles.size(), max / 4);  // the smallest cube that fits: not far below
    std::set<std::uint32_t> sources(shown.source.begin(), shown.source.end());
    EXPECT_EQ(sources.size(), shown.source.size());
    const double whole = area_of(mesh.vertices, mesh.triangles), kept = area_of(shown.vertices, shown.triangles);
    EXPECT_NEAR(kept / whole, 1.0, 0.1);
    // Each kept triangle faces as its source does.
    for (std::size_t t = 0; t < shown.triangles.size(); ++t) {
        const auto& k = shown.triangles[t];
        const Vec3 n = (shown.vertices[static_cast<std::size_t>(k[1])] - shown.vertices[static_cast<std::size_t>(k[0])])
                           .cross(shown.vertices[static_cast<std::size_t>(k[2])] - shown.vertices[static_cast<std::size_t>(k[0])]);
        const std::size_t s = shown.source[t];
        const Vec3 m = (mesh.corner(s, 1) - mesh.corner(s, 0)).cross(mesh.corner(s, 2) - mesh.corner(s, 0));
        EXPECT_GT(n.dot(m), 0.0) << t;
    }
}

}  // namespace vertex_clustering_cases
}  // namespace peensim
