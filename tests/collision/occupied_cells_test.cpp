// OccupiedCells, the summed-volume table of the cells a triangle may meet, which lets
// MeshCollider::first_hit answer a sweep with nothing in reach without walking its BVH. Its one
// promise: "no marked cell in this box" only where no point of any triangle lies in the box. Tested
// with boxes around points of every triangle (corners, edges, inside; down to a nanometre wide,
// on cell faces and corners), boxes beyond the mesh, and how sharp it is inside a closed box.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "collision/occupied_cells.h"
#include "geometry/box_mesh.h"
#include "geometry/cylinder_mesh.h"

namespace peensim {
namespace {

// A tilted plate of two large triangles, a box of quads and a tube: flat, coarse and fine meshes,
// faces along the grid's axes and across them.
std::vector<TriangleMesh> meshes() {
    std::vector<TriangleMesh> out;
    TriangleMesh plate;
    plate.vertices = {Vec3(-0.05, -0.04, 0.01), Vec3(0.06, -0.03, 0.03), Vec3(0.05, 0.05, -0.02), Vec3(-0.04, 0.06, -0.035)};
    plate.triangles = {{0, 1, 2}, {0, 2, 3}};
    out.push_back(plate);
    BoxSpec spec;
    spec.size_m = Vec3(0.2, 0.15, 0.1);
    spec.center_m = Vec3(0.01, -0.02, 0.03);
    spec.divisions = Eigen::Vector3i(7, 5, 3);
    out.push_back(box(spec));
    CylinderSpec tube;
    tube.radius_m = 0.01;
    tube.height_m = 0.03;
    tube.segments = 200;
    tube.axial_subdivisions = 10;
    tube.axis = Axis::y;
    tube.capped = false;
    out.push_back(cylinder(tube));
    return out;
}

// A point of triangle t at barycentric (u, v).
Vec3 on_triangle(const TriangleMesh& mesh, std::size_t t, double u, double v) {
    const Vec3 a = mesh.corner(t, 0), b = mesh.corner(t, 1), c = mesh.corner(t, 2);
    return a + u * (b - a) + v * (c - a);
}

TEST(OccupiedCells, EveryBoxHoldingAPointOfATriangleIsOccupied) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    for (const TriangleMesh& mesh : meshes()) {
        for (const double cells : {64.0, 5000.0, OccupiedCells::kDefaultCells}) {
            const OccupiedCells grid(mesh, cells);
            const double h = grid.cell_size();
            int tested = 0;
            for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
                for (int s = 0; s < 40; ++s) {
                    double u = u01(rng), v = u01(rng);
                    if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
                    if (s < 3) u = s == 1 ? 1.0 : 0.0, v = s == 2 ? 1.0 : 0.0;  // the corners
                    if (s >= 3 && s < 6) v = 0.0;                               // an edge
                    const Vec3 p = on_triangle(mesh, t, u, v);
                    // Boxes from a nanometre to a few cells, centred on the point or with the point
                    // on a face or a corner of the box.
                    for (const double half : {1e-9, 0.01 * h, 0.5 * h, 3.0 * h}) {
                        const Vec3 shift = Vec3(u01(rng) - 0.5, u01(rng) - 0.5, u01(rng) - 0.5) * (s % 2 == 0 ? 0.0 : 2.0 * half);
                        const Vec3 lo = p - Vec3::Constant(half) + shift, hi = p + Vec3::Constant(half) + shift;
                        const Vec3 inside_lo = lo.cwiseMin(p), inside_hi = hi.cwiseMax(p);
                        ASSERT_TRUE(grid.any_in(inside_lo, inside_hi))
                            << "triangle " << t << " point (" << p.transpose() << ") box " << inside_lo.transpose() << " .. "
                            << inside_hi.transpose() << " cell " << h;
                        ++tested;
                    }
                    // A degenerate box: the point itself.
                    ASSERT_TRUE(grid.any_in(p, p)) << "triangle " << t << " point (" << p.transpose() << ")";
                }
            }
            EXPECT_EQ(tested, static_cast<int>(mesh.triangle_count()) * 40 * 4);
        }
    }
}

TEST(OccupiedCells, BoxesBeyondTheMeshAreEmptyAndUnreadableOnesRuleNothingOut) {
    // A box that holds the whole mesh is occupied, one more than two cells beyond its bounds on
    // any side is not; an inverted box holds nothing, and a non-finite one rules nothing out.
    for (const TriangleMesh& mesh : meshes()) {
        const OccupiedCells grid(mesh, 20000.0);
        EXPECT_GT(grid.marked(), 0u);
        EXPECT_LT(grid.marked(), grid.cell_count());
        Vec3 lo = mesh.vertices.front(), hi = lo;
        for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
        EXPECT_TRUE(grid.any_in(lo, hi));
        EXPECT_TRUE(grid.any_in(lo - Vec3::Constant(1.0), hi + Vec3::Constant(1.0)));
        // Beyond the mesh's bounds by more than two cells on one axis: nothing.
        const double h = grid.cell_size();
        for (int k = 0; k < 3; ++k) {
            Vec3 far_lo = lo, far_hi = hi;
            far_lo[k] = hi[k] + 2.0 * h;
            far_hi[k] = hi[k] + 5.0 * h;
            EXPECT_FALSE(grid.any_in(far_lo, far_hi)) << "axis " << k;
            far_lo = lo, far_hi = hi;
            far_lo[k] = lo[k] - 5.0 * h;
            far_hi[k] = lo[k] - 2.0 * h;
            EXPECT_FALSE(grid.any_in(far_lo, far_hi)) << "axis " << k;
        }
        // An inverted box holds nothing; a box with a non-finite side rules nothing out.
        EXPECT_FALSE(grid.any_in(hi, lo));
        EXPECT_TRUE(grid.any_in(lo, Vec3(hi.x(), std::numeric_limits<double>::infinity(), hi.z())));
        EXPECT_TRUE(grid.any_in(Vec3::Constant(std::nan("")), hi));
    }
}

TEST(OccupiedCells, ItIsSharpAwayFromTheSurface) {
    // Inside the box mesh (a closed chamber of quads), a box more than two cell diagonals from every
    // wall is empty: the gate answers there. Points on a regular lattice of the inside.
    BoxSpec spec;
    spec.size_m = Vec3(0.2, 0.15, 0.1);
    spec.divisions = Eigen::Vector3i(7, 5, 3);
    const TriangleMesh mesh = box(spec);
    const OccupiedCells grid(mesh);
    const double h = grid.cell_size(), clear = 2.0 * std::sqrt(3.0) * h;
    int empty = 0, lattice = 0;
    for (double x = -0.1; x <= 0.1; x += 0.01)
        for (double y = -0.075; y <= 0.075; y += 0.01)
            for (double z = -0.05; z <= 0.05; z += 0.01) {
                const Vec3 p(x, y, z);
                const double wall = std::min({0.1 - std::abs(x), 0.075 - std::abs(y), 0.05 - std::abs(z)});
                if (!(wall > clear + 0.003)) continue;
                ++lattice;
                empty += !grid.any_in(p - Vec3::Constant(0.003), p + Vec3::Constant(0.003));
            }
    EXPECT_GT(lattice, 100);
    EXPECT_EQ(empty, lattice);
}

TEST(OccupiedCells, AMeshWithoutTrianglesHoldsNothing) {
    const OccupiedCells grid(TriangleMesh{});
    EXPECT_FALSE(grid.any_in(Vec3::Constant(-1.0), Vec3::Constant(1.0)));
    EXPECT_EQ(grid.memory_bytes(), 0u);
}

}  // namespace
}  // namespace peensim
