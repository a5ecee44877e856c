// The shipped meshes of assets/ (written by assets/regenerate.sh): each loads, the solids are
// closed and outward, the chambers are open only at the bottom and face their cavity, and the
// parts fit together (sonotrode inside the chamber, axle inside the gear's bore).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "geometry/mesh_checks.h"
#include "geometry/mesh_loader.h"

namespace peensim {
namespace {

constexpr double kMm = 1e-3;  // m per mm (the assets' unit)

TriangleMesh asset(const std::string& name) { return load_mesh(std::string(PEENSIM_SOURCE_DIR) + "/assets/" + name, kMm); }

void expect_bounds_mm(const TriangleMesh& m, Vec3 lo, Vec3 hi) {
    const Bounds b = bounds(m);
    EXPECT_LT((b.min_m - lo * kMm).cwiseAbs().maxCoeff(), 1e-6 * kMm) << b.min_m.transpose() / kMm;
    EXPECT_LT((b.max_m - hi * kMm).cwiseAbs().maxCoeff(), 1e-6 * kMm) << b.max_m.transpose() / kMm;
}

void expect_closed_solid(const TriangleMesh& m) {
    EXPECT_TRUE(is_closed(m));
    EXPECT_EQ(edge_report(m).misoriented_edges, 0u);
    EXPECT_GT(enclosed_volume(m), 0.0);
}

// Smallest and largest distance (m) from the axis through the origin along `axis` to the
// triangles, in the plane across the axis (edges projected onto it).
double closest_to_axis(const TriangleMesh& m, int axis) {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    double closest = INFINITY;
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector2d p(m.corner(t, k)[a], m.corner(t, k)[b]);
            const Eigen::Vector2d q(m.corner(t, (k + 1) % 3)[a], m.corner(t, (k + 1) % 3)[b]);
            const Eigen::Vector2d d = q - p;
            const double s = d.squaredNorm() > 0.0 ? std::clamp(-p.dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
            closest = std::min(closest, (p + s * d).norm());
        }
    }
    return closest;
}

double farthest_from_axis(const TriangleMesh& m, int axis) {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    double farthest = 0.0;
    for (const Vec3& v : m.vertices) farthest = std::max(farthest, std::hypot(v[a], v[b]));
    return farthest;
}

// True if every corner of triangle t lies at z_lo_mm <= z <= z_hi_mm, radius_mm from the z axis.
bool on_wall_between(const TriangleMesh& m, const std::array<int, 3>& t, double z_lo_mm, double z_hi_mm, double radius_mm) {
    for (int k : t) {
        const Vec3& v = m.vertices[static_cast<std::size_t>(k)];
        if (v.z() < z_lo_mm * kMm - 1e-9 || v.z() > z_hi_mm * kMm + 1e-9) return false;
        if (std::abs(std::hypot(v.x(), v.y()) - radius_mm * kMm) > 1e-6 * kMm) return false;
    }
    return true;
}

TEST(GeometryAssets, RodCase) {
    const TriangleMesh chamber = asset("rod-chamber.stl");
    const EdgeReport r = edge_report(chamber);
    EXPECT_EQ(r.boundary_edges, 4u);  // the rim of the missing floor
    EXPECT_EQ(r.non_manifold_edges + r.misoriented_edges, 0u);
    expect_bounds_mm(chamber, Vec3(-30, -15, -5), Vec3(30, 15, 40));
    for (std::size_t t = 0; t < chamber.triangle_count(); ++t) {
        const Vec3 centroid = (chamber.corner(t, 0) + chamber.corner(t, 1) + chamber.corner(t, 2)) / 3.0;
        EXPECT_LT(triangle_normal(chamber, t).dot(centroid - Vec3(0, 0, 0.0175)), 0.0);  // faces the cavity
    }

    const TriangleMesh sonotrode = asset("rod-sonotrode.stl");
    expect_closed_solid(sonotrode);
    expect_bounds_mm(sonotrode, Vec3(-30, -15, -5), Vec3(30, 15, 0));
    EXPECT_NEAR(enclosed_volume(sonotrode), 60 * 30 * 5 * std::pow(kMm, 3), 1e-12);

    const TriangleMesh rod = asset("rod.stl");
    expect_closed_solid(rod);
    expect_bounds_mm(rod, Vec3(-5, -15, 15), Vec3(5, 15, 25));
    EXPECT_NEAR(enclosed_volume(rod), std::numbers::pi * 25 * 30 * std::pow(kMm, 3), 2e-3 * enclosed_volume(rod));
}

TEST(GeometryAssets, GearCase) {
    const TriangleMesh chamber = asset("gear-chamber.stl");
    const EdgeReport r = edge_report(chamber);
    EXPECT_EQ(r.boundary_edges, 128u);  // the open bottom rim
    EXPECT_EQ(r.non_manifold_edges + r.misoriented_edges, 0u);
    expect_bounds_mm(chamber, Vec3(-40, -40, -10), Vec3(40, 40, 75));

    const TriangleMesh sonotrode = asset("gear-sonotrode.stl");
    expect_closed_solid(sonotrode);
    expect_bounds_mm(sonotrode, Vec3(-29.9, -29.9, -10), Vec3(29.9, 29.9, 0));
    // The disk fits inside the lower section's polygon (inscribed radius 30 cos(pi / 128)).
    TriangleMesh lower_wall = chamber;
    std::erase_if(lower_wall.triangles, [&](const auto& t) { return !on_wall_between(lower_wall, t, -10, 15, 30); });
    const double clearance = closest_to_axis(lower_wall, 2) - farthest_from_axis(sonotrode, 2);
    EXPECT_GT(clearance, 0.05 * kMm);
    EXPECT_LT(clearance, 0.2 * kMm);

    const TriangleMesh gear = asset("gear.stl");
    expect_closed_solid(gear);
    EXPECT_NEAR(static_cast<double>(gear.triangle_count()), 5000.0, 500.0);
    expect_bounds_mm(gear, Vec3(-22, -5, -22), Vec3(22, 5, 22));

    const TriangleMesh axle = asset("axle.stl");
    expect_closed_solid(axle);
    expect_bounds_mm(axle, Vec3(-4.95, -39, -4.95), Vec3(4.95, 39, 4.95));
    // The axle passes through the bore without touching it.
    EXPECT_GT(closest_to_axis(gear, 1), farthest_from_axis(axle, 1));
    // Placed at z = 42 mm (the scene's placement), the gear stays below the lid and the axle's
    // ends inside the upper section's wall.
    EXPECT_LT(42 * kMm + bounds(gear).max_m.z(), 75 * kMm);
    EXPECT_GT(42 * kMm + bounds(gear).min_m.z(), 15 * kMm);
    TriangleMesh upper_wall = chamber;
    std::erase_if(upper_wall.triangles, [&](const auto& t) { return !on_wall_between(upper_wall, t, 15, 75, 40); });
    EXPECT_GT(closest_to_axis(upper_wall, 2), farthest_from_axis(axle, 2));
}

TEST(GeometryAssets, AlmenStripTypeA) {
    // SAE J442 type A: 76.2 x 19.0 x 1.29 mm, back face on z = 0, peened face up.
    const TriangleMesh strip = asset("almen-strip-a.stl");
    expect_closed_solid(strip);
    // (Binary STL holds float32: 38.1 mm is stored as 38.099998 mm.)
    const Bounds b = bounds(strip);
    EXPECT_LT((b.min_m - Vec3(-38.1, -9.5, 0) * kMm).cwiseAbs().maxCoeff(), 1e-5 * kMm);
    EXPECT_LT((b.max_m - Vec3(38.1, 9.5, 1.29) * kMm).cwiseAbs().maxCoeff(), 1e-5 * kMm);
    // scenes/almen.yaml turns it over at z = 42 mm in the gear chamber: its corners stay inside
    // the upper section (radius 40 mm above the step at 15 mm).
    EXPECT_LT(std::hypot(38.1, 9.5), 40.0 * std::cos(M_PI / 128));
}

}  // namespace
}  // namespace peensim
