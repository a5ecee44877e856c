// The room a part takes (geometry/part_envelope.h): a box's bounds and footprint, still and
// turning about each axis, against the closed forms of its corners.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/box_mesh.h"
#include "geometry/part_envelope.h"

namespace peensim {
namespace {

constexpr double kTight = 1e-12;  // m: sums of a few products of millimetres

// A 10 x 20 x 30 mm box whose centre is off the origin: half sizes a, b, c.
constexpr double a = 5e-3, b = 10e-3, c = 15e-3;
const Vec3 kCentre(7e-3, -3e-3, 40e-3);

TriangleMesh off_centre_box() {
    BoxSpec spec;
    spec.size_m = Vec3(2 * a, 2 * b, 2 * c);
    spec.center_m = kCentre;
    spec.divisions = Eigen::Vector3i(3, 2, 4);
    return box(spec);
}

void expect_near(const Vec3& got, const Vec3& want) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], kTight) << "component " << k;
}

TEST(PartEnvelope, AStillPartIsItsBoundsAndItsFootprintTheHalfDiagonalAcross) {
    const PartEnvelope e = part_envelope(off_centre_box(), std::nullopt);
    expect_near(e.centre_m, kCentre);
    expect_near(e.size_m, Vec3(2 * a, 2 * b, 2 * c));
    expect_near(e.lo_m, kCentre - Vec3(a, b, c));
    expect_near(e.hi_m, kCentre + Vec3(a, b, c));
    EXPECT_EQ(e.swept_radius_m, 0.0);
    EXPECT_NEAR(e.footprint_radius_m, std::hypot(a, b), kTight);  // measured from the vertical line through the centre
}

TEST(PartEnvelope, ATurningPartSweepsItsCornersCircles) {
    // About y: the corners are sqrt(a^2 + c^2) from the axis, and reach b along it; level, so the
    // farthest point from the vertical line is a corner's circle lying level: sqrt(b^2 + a^2 + c^2).
    const double rho_y = std::hypot(a, c);
    const PartEnvelope y = part_envelope(off_centre_box(), Axis::y);
    EXPECT_NEAR(y.swept_radius_m, rho_y, kTight);
    expect_near(y.lo_m, kCentre - Vec3(rho_y, b, rho_y));
    expect_near(y.hi_m, kCentre + Vec3(rho_y, b, rho_y));
    EXPECT_NEAR(y.footprint_radius_m, std::sqrt(a * a + b * b + c * c), kTight);
    expect_near(y.size_m, Vec3(2 * a, 2 * b, 2 * c));  // the part's own size stays

    const double rho_x = std::hypot(b, c);
    const PartEnvelope x = part_envelope(off_centre_box(), Axis::x);
    expect_near(x.lo_m, kCentre - Vec3(a, rho_x, rho_x));
    EXPECT_NEAR(x.footprint_radius_m, std::sqrt(a * a + b * b + c * c), kTight);

    // About the upright axis the heights stay and the footprint is the swept radius.
    const double rho_z = std::hypot(a, b);
    const PartEnvelope z = part_envelope(off_centre_box(), Axis::z);
    expect_near(z.lo_m, kCentre - Vec3(rho_z, rho_z, c));
    expect_near(z.hi_m, kCentre + Vec3(rho_z, rho_z, c));
    EXPECT_NEAR(z.footprint_radius_m, rho_z, kTight);
}

}  // namespace
}  // namespace peensim
