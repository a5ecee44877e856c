// Shot placement with a closed part over the sonotrode: the layers grow up to and around the part,
// and no shot may start inside it. The enclosure counts a closed part's inside as enclosed free
// space too (it is cut off from the outside); placement used to fill it with shot whenever the
// layers reached it (the extremes matrix's 3072 shot of 2 mm: 130 centres inside the rod, then
// deep penetrations and impacts from inside the rod in both schemes).
#include <gtest/gtest.h>

#include <cmath>

#include "model/shot_placement.h"
#include "support/test_scene.h"

namespace peensim {
namespace {

using testing::PartShape;
using testing::PartSpec;
using testing::TestScene;
using testing::TestSceneSpec;

// Signed distance (m) from p to an axis-aligned box: negative inside.
double box_distance(const Vec3& p, const Vec3& centre, const Vec3& size) {
    const Vec3 q = (p - centre).cwiseAbs() - 0.5 * size;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

TestSceneSpec dense_load(const PartSpec& part) {
    TestSceneSpec spec;
    spec.chamber_size_m = Vec3(20e-3, 20e-3, 20e-3);
    spec.shot_diameter_m = 1e-3;
    spec.shot_count = 2400;  // ~9 layers of ~280: well above the part's lower face at 4 mm
    spec.part = part;
    return spec;
}

TEST(ShotPlacement, NoShotStartsInsideABoxPartTheLayersReach) {
    PartSpec box;
    box.shape = PartShape::box;
    box.size_m = Vec3(12e-3, 12e-3, 6e-3);
    box.center_m = Vec3(0.0, 0.0, 7e-3);  // from 4 mm to 10 mm above the plate
    const TestScene scene(dense_load(box));
    const auto model = scene.compile();
    const InitialShots shots = place_shots(*model);
    ASSERT_EQ(static_cast<int>(shots.positions.size()), 2400);
    const double R = 0.5e-3;
    int inside = 0, above_part_bottom = 0;
    double closest = 1.0;
    for (const Vec3& p : shots.positions) {
        const double d = box_distance(p, box.center_m, box.size_m);
        closest = std::min(closest, d);
        if (d < 0.0) ++inside;
        if (p.z() > 4e-3) ++above_part_bottom;
    }
    EXPECT_EQ(inside, 0);
    EXPECT_GE(closest, R) << "a shot overlaps the part";
    // The layers did reach the part's height: the shot beside it, not in it.
    EXPECT_GT(above_part_bottom, 100);
}

TEST(ShotPlacement, NoShotStartsInsideACylinderPartTheLayersReach) {
    PartSpec rod;
    rod.shape = PartShape::cylinder;
    rod.radius_m = 4e-3;
    rod.length_m = 16e-3;
    rod.axis = Axis::y;
    rod.segments = 96;
    rod.center_m = Vec3(0.0, 0.0, 7e-3);  // from 3 mm to 11 mm above the plate
    const TestScene scene(dense_load(rod));
    const auto model = scene.compile();
    const InitialShots shots = place_shots(*model);
    ASSERT_EQ(static_cast<int>(shots.positions.size()), 2400);
    int inside = 0, beside = 0;
    for (const Vec3& p : shots.positions) {
        const double radial = std::hypot(p.x() - rod.center_m.x(), p.z() - rod.center_m.z());
        const bool within_length = std::abs(p.y()) < 0.5 * rod.length_m;
        if (within_length && radial < rod.radius_m) ++inside;
        if (p.z() > 7e-3) ++beside;
    }
    EXPECT_EQ(inside, 0);
    EXPECT_GT(beside, 50);
}

TEST(ShotPlacement, SmallShotUseThePlateUpToTheWallsOnACoarseGrid) {
    // 0.1 mm shot in a 20 mm chamber: cells of R / 2 would take ~600 M; the enclosure's grid is
    // coarsened to ~8 M cells (2 R each), and a centre hugging a wall lies in a cell the wall
    // touches. It must still count as inside: the chamber is closed and the band along the walls
    // is used like the rest of the plate.
    TestSceneSpec spec;
    spec.shot_diameter_m = 0.1e-3;
    spec.shot_count = 3000;
    const TestScene scene(spec);
    const auto model = scene.compile();
    const InitialShots shots = place_shots(*model);
    ASSERT_EQ(static_cast<int>(shots.positions.size()), 3000);
    const double R = 0.05e-3, half = 10e-3;
    int hugging = 0;
    for (const Vec3& p : shots.positions) {
        const double to_wall = half - std::max(std::abs(p.x()), std::abs(p.y()));
        EXPECT_GE(to_wall, R);
        hugging += to_wall < 2.0 * R;
    }
    // The band within one radius of its innermost position holds R / (20 mm / 2 / 4) of the area: ~60 shot.
    EXPECT_GT(hugging, 20);
    EXPECT_EQ(shots.layers, 1);
}

}  // namespace
}  // namespace peensim
