// close_up_of: the view the analysis puts in place of its last fixed view for a small area (the
// slowest region, the area out of reach). A patch of one face of a box is looked at from outside,
// into the face, framed with its margin, in the world (the part's pose applied); the whole box, a
// large face, or a patch that faces both ways get no close-up.
#include "render/close_up.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "geometry/box_mesh.h"
#include "geometry/mesh_checks.h"

namespace peensim {
namespace {

// A 100 x 100 x 20 mm box of 10 x 10 x 2 quads a face, turned 90 deg about z and moved 1 m up x.
Component box_part() {
    Component c;
    c.mesh = std::make_shared<TriangleMesh>(box(BoxSpec{Vec3(0.1, 0.1, 0.02), Vec3::Zero(), Eigen::Vector3i(10, 10, 2)}));
    c.kinematics.rest.rotation = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()).toRotationMatrix();
    c.kinematics.rest.translation = Vec3(1.0, 0.0, 0.0);
    return c;
}

// Weight 1 on the triangles whose centres `pick` chooses.
template <class Pick>
std::vector<double> weights(const TriangleMesh& mesh, Pick&& pick) {
    std::vector<double> w(mesh.triangle_count(), 0.0);
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
        if (pick((mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0, triangle_normal(mesh, t))) w[t] = 1.0;
    return w;
}

TEST(CloseUp, ASmallPatchIsSeenFromOutsideIntoItsFaceWithItsMargin) {
    const Component part = box_part();
    // The top face's quad at x, y in [0, 10] mm: 10 x 10 mm of a 100 mm box.
    const auto w = weights(
        *part.mesh, [](const Vec3& c, const Vec3& n) { return n.z() > 0.9 && c.x() > 0.0 && c.x() < 0.01 && c.y() > 0.0 && c.y() < 0.01; });
    const auto close = close_up_of(part, w, "spot");
    ASSERT_TRUE(close.has_value());
    EXPECT_EQ(close->name, "close-up of spot");
    EXPECT_TRUE(close->direction.isApprox(Vec3(0, 0, -1), 1e-12)) << close->direction.transpose();  // down into the top face
    ASSERT_EQ(close->points_m.size(), 8u);
    // The patch's bounds (0..10 mm, 0..10 mm, z = 10 mm) grown by max(2.5 mm, 104 mm / 40 = 2.6 mm),
    // then turned and moved: x' = 1 m - y, y' = x.
    const double margin = std::sqrt(0.1 * 0.1 + 0.1 * 0.1 + 0.02 * 0.02) / 40.0;
    Vec3 lo = close->points_m.front(), hi = lo;
    for (const Vec3& p : close->points_m) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    EXPECT_NEAR(lo.x(), 1.0 - 0.01 - margin, 1e-12);
    EXPECT_NEAR(hi.x(), 1.0 + margin, 1e-12);
    EXPECT_NEAR(lo.y(), -margin, 1e-12);
    EXPECT_NEAR(hi.y(), 0.01 + margin, 1e-12);
    EXPECT_NEAR(lo.z(), 0.01 - margin, 1e-12);
    EXPECT_NEAR(hi.z(), 0.01 + margin, 1e-12);
}

TEST(CloseUp, ALargeAreaOrOneThatFacesEveryWayHasNone) {
    const Component part = box_part();
    const TriangleMesh& mesh = *part.mesh;
    EXPECT_FALSE(close_up_of(part, weights(mesh, [](const Vec3&, const Vec3&) { return true; }), "all"));
    EXPECT_FALSE(close_up_of(part, weights(mesh, [](const Vec3&, const Vec3& n) { return n.z() > 0.9; }), "top"));
    // The same 10 x 10 mm patch on the top and on the bottom face: small (24.5 mm of a 104 mm
    // box), but facing up and down alike, so no side to look from.
    const auto both = weights(mesh, [](const Vec3& c, const Vec3& n) {
        return std::abs(n.z()) > 0.9 && c.x() > 0.0 && c.x() < 0.01 && c.y() > 0.0 && c.y() < 0.01;
    });
    EXPECT_FALSE(close_up_of(part, both, "both sides"));
    const auto top_only = weights(
        mesh, [](const Vec3& c, const Vec3& n) { return n.z() > 0.9 && c.x() > 0.0 && c.x() < 0.01 && c.y() > 0.0 && c.y() < 0.01; });
    EXPECT_TRUE(close_up_of(part, top_only, "top only"));
    EXPECT_FALSE(close_up_of(part, std::vector<double>(mesh.triangle_count(), 0.0), "nothing"));
}

}  // namespace
}  // namespace peensim
