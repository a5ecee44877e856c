// The reach test the coverage samples are sorted by: a point takes the answer of a recent distance
// query near it when the shot centre's clearance leaves room (facet_reach.cpp's anchors), and that
// answer is always the one the plain test (shot_fits_beside) gives, on a solid part, on an open
// chamber wall (both sides), whatever order the points come in, and at the corners of neighbouring
// triangles (which share anchors across triangles of other normals).
#include <gtest/gtest.h>

#include <string>

#include "common/random.h"
#include "geometry/mesh_checks.h"
#include "model/facet_reach.h"
#include "model/shot_cavity.h"
#include "scene/scene_parser.h"

namespace peensim {
namespace {

struct ReachTally {
    long points = 0, reached = 0, mixed_triangles = 0;
};

// Every `stride`-th triangle of component ci, on a grid of n x n sub-triangle points walked row by
// row (as the coverage samples are), then the same points in a scrambled order: the anchored test
// against the plain one at each.
ReachTally compare(const Model& model, ShotCavity& cavity, std::size_t ci, std::size_t stride, int n) {
    const Component& c = model.components[ci];
    const Pose pose = c.kinematics.pose(SimTime{});
    const double R = model.min_shot_radius_m;
    const auto reach = reach_test(model, ci, &cavity);
    const TriangleMesh& mesh = *c.mesh;
    ReachTally tally;
    Random order(7);
    const auto walk = [&](std::size_t t, int n, bool scramble) {
        const Vec3 a = mesh.corner(t, 0), ab = mesh.corner(t, 1) - a, ac = mesh.corner(t, 2) - a;
        const Vec3 normal = pose.rotation * triangle_normal(mesh, t);
        std::vector<Vec3> points;
        for (int i = 0; i <= n; ++i)
            for (int j = 0; i + j <= n; ++j) points.push_back(a + (double(i) / n) * ab + (double(j) / n) * ac);
        if (scramble)  // far jumps and returns
            for (std::size_t k = points.size(); k > 1; --k) std::swap(points[k - 1], points[order.next() % k]);
        long reached = 0;
        for (const Vec3& p : points) {
            const bool plain = shot_fits_beside(model, &cavity, c, pose.to_world(p), normal, R);
            EXPECT_EQ(reach(p, t, R), plain) << "component " << ci << " triangle " << t << " points " << n;
            ++tally.points;
            reached += plain ? 1 : 0;
        }
        tally.reached += reached;
        return reached > 0 && reached < static_cast<long>(points.size());
    };
    for (std::size_t t = 0; t < mesh.triangle_count(); t += stride) {
        const bool mixed = walk(t, n, false);
        walk(t, n, true);
        if (!mixed) continue;
        // Where the answer flips: finer, so that points lie just beyond an anchor's reach.
        ++tally.mixed_triangles;
        walk(t, 6 * n, false);
    }
    return tally;
}

TEST(FacetReach, TheAnchoredTestAnswersAsThePlainOneEverywhere) {
    const auto model = compile_model(parse_scene_file(std::string(PEENSIM_SOURCE_DIR) + "/scenes/gear.yaml"));
    Random rng(model->seed);
    ShotCavity cavity(*model, rng);
    std::size_t gear = 0, chamber = 0;
    for (std::size_t ci = 0; ci < model->components.size(); ++ci) {
        if (model->description.components[ci].name == "gear") gear = ci;
        if (model->components[ci].role == ComponentRole::chamber) chamber = ci;
    }
    ASSERT_TRUE(model->components[gear].solid);
    ASSERT_FALSE(model->components[chamber].solid);  // its walls are probed on both sides
    const ReachTally g = compare(*model, cavity, gear, 11, 24);
    const ReachTally w = compare(*model, cavity, chamber, 13, 12);
    // Both answers, and triangles that hold both (where the anchors are used and could go wrong).
    EXPECT_GT(g.reached, g.points / 4);
    EXPECT_LT(g.reached, g.points);
    EXPECT_GT(g.mixed_triangles, 10);
    EXPECT_GT(w.reached, 0);
    // Every triangle in turn, its corners only (a fine mesh's probes): the corners it shares with
    // the last few triangles take their anchors, probed along another normal.
    const ReachTally corners = compare(*model, cavity, gear, 1, 1);
    EXPECT_GT(corners.reached, corners.points / 4);
    EXPECT_LT(corners.reached, corners.points);
}

}  // namespace
}  // namespace peensim
