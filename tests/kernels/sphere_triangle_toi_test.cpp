// Exact shot-triangle times of impact against closed forms: a drop on a face, straight runs into an
// edge and a vertex, grazing passes (double roots), the state at the start of the interval
// (overlap, touching while approaching, touching while separating right after a bounce), and a
// randomized check that no contact is missed or reported early, against dense sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/sphere_triangle_toi.h"

namespace peensim {
namespace {

constexpr double kG = 9.81;  // m/s^2
constexpr double kR = 1e-3;  // m, shot radius
const Vec3 kToiGravity(0, 0, -kG);

double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    return (p - closest_point_on_triangle(p, a, b, c).point).norm();
}

// A large horizontal triangle in z = 0 around the origin.
struct Floor {
    Vec3 a{-0.02, -0.02, 0}, b{0.02, -0.02, 0}, c{0.0, 0.02, 0};
};

TEST(EventSphereTriangle, DropFromRestMatchesFreeFall) {
    const Floor f;
    for (double h : {1e-4, 0.02, 0.5}) {  // m, fall to contact
        const double t0 = 0.37;           // s, an arbitrary start
        const Trajectory path{Vec3(0.001, -0.002, h + kR), Vec3::Zero(), kToiGravity, t0};
        TriangleContact contact;
        ASSERT_EQ(sphere_triangle_toi(path, kR, f.a, f.b, f.c, t0, t0 + 1.0, contact), ToiStatus::impact);
        const double fall = std::sqrt(2.0 * h / kG);
        EXPECT_NEAR(contact.time - t0, fall, 1e-12 * fall) << h;
        EXPECT_EQ(contact.feature, TriangleFeature::face);
        EXPECT_NEAR((contact.normal - Vec3::UnitZ()).norm(), 0.0, 1e-15);
        EXPECT_NEAR((contact.point - Vec3(0.001, -0.002, 0)).norm(), 0.0, 1e-15);
        // An interval that ends before the contact misses it.
        EXPECT_EQ(sphere_triangle_toi(path, kR, f.a, f.b, f.c, t0, t0 + 0.999 * fall, contact), ToiStatus::miss);
    }
}

TEST(EventSphereTriangle, DropOnTheUndersideAndThrowUpward) {
    // The kernel is two-sided: a shot thrown up at a ceiling (normal pointing away from it).
    const Floor f;
    const double vz = 2.0, gap = 0.05;  // m/s, m between centre and ceiling minus R
    const Trajectory path{Vec3(0, 0, -gap - kR), Vec3(0, 0, vz), kToiGravity, 0.0};
    TriangleContact contact;
    ASSERT_EQ(sphere_triangle_toi(path, kR, f.a, f.b, f.c, 0.0, 1.0, contact), ToiStatus::impact);
    const double t = (vz - std::sqrt(vz * vz - 2.0 * kG * gap)) / kG;  // first root of gap = vz t - g t^2 / 2
    EXPECT_NEAR(contact.time, t, 1e-12 * t);
    EXPECT_NEAR((contact.normal + Vec3::UnitZ()).norm(), 0.0, 1e-15);
}

// Triangles whose corner k (k = 0, 1, 2 in turn) is the origin with the triangle lying at x <= 0.
// Returns corners; the features the origin and the edge from it along -y have are reported.
struct Rotated {
    Vec3 corner[3];
    TriangleFeature vertex, edge;
};
Rotated edge_and_vertex_case(int k, const Vec3& p, const Vec3& q, const Vec3& r) {
    // Corner k gets p, the next q, the one after r: the edge (k, k+1) is p-q.
    Rotated out;
    out.corner[k] = p;
    out.corner[(k + 1) % 3] = q;
    out.corner[(k + 2) % 3] = r;
    const TriangleFeature vertices[3] = {TriangleFeature::vertex_a, TriangleFeature::vertex_b, TriangleFeature::vertex_c};
    const TriangleFeature edges[3] = {TriangleFeature::edge_ab, TriangleFeature::edge_bc, TriangleFeature::edge_ca};
    out.vertex = vertices[k];
    out.edge = edges[k];
    return out;
}

TEST(EventSphereTriangle, StraightRunIntoAnEdge) {
    // Edge along y at x = 0 in z = 0; the triangle extends to x < 0. Without gravity the centre
    // (d, y, z) moves along -x at v: contact when x^2 + z^2 = R^2, t = (d - sqrt(R^2 - z^2)) / v.
    const double d = 0.01, v = 1.5, y = 0.003;
    for (int k = 0; k < 3; ++k) {
        const Rotated tri = edge_and_vertex_case(k, Vec3(0, 0.01, 0), Vec3(0, -0.01, 0), Vec3(-0.02, 0, 0));
        for (double z : {0.0, 0.6 * kR, -0.3 * kR}) {
            const Trajectory path{Vec3(d, y, z), Vec3(-v, 0, 0), Vec3::Zero(), 0.0};
            TriangleContact contact;
            ASSERT_EQ(sphere_triangle_toi(path, kR, tri.corner[0], tri.corner[1], tri.corner[2], 0.0, 1.0, contact), ToiStatus::impact);
            const double x = std::sqrt(kR * kR - z * z);
            const double t = (d - x) / v;
            EXPECT_NEAR(contact.time, t, 1e-12 * t) << k << " " << z;
            EXPECT_EQ(contact.feature, tri.edge);
            EXPECT_NEAR((contact.point - Vec3(0, y, 0)).norm(), 0.0, 1e-15);
            EXPECT_NEAR((contact.normal - Vec3(x, 0, z) / kR).norm(), 0.0, 1e-9);
        }
    }
}

TEST(EventSphereTriangle, StraightRunIntoAVertex) {
    // The origin is a corner whose edges recede towards -x; the centre (d, 0, z) moves along -x.
    const double d = 0.01, v = 0.8;
    for (int k = 0; k < 3; ++k) {
        const Rotated tri = edge_and_vertex_case(k, Vec3(0, 0, 0), Vec3(-0.01, -0.005, 0), Vec3(-0.01, 0.005, 0));
        for (double z : {0.0, 0.3 * kR}) {
            const Trajectory path{Vec3(d, 0, z), Vec3(-v, 0, 0), Vec3::Zero(), 0.0};
            TriangleContact contact;
            ASSERT_EQ(sphere_triangle_toi(path, kR, tri.corner[0], tri.corner[1], tri.corner[2], 0.0, 1.0, contact), ToiStatus::impact);
            const double x = std::sqrt(kR * kR - z * z);
            const double t = (d - x) / v;
            EXPECT_NEAR(contact.time, t, 1e-12 * t) << k << " " << z;
            EXPECT_EQ(contact.feature, tri.vertex);
            EXPECT_EQ(contact.point, Vec3::Zero());
            EXPECT_NEAR((contact.normal - Vec3(x, 0, z) / kR).norm(), 0.0, 1e-9);
        }
    }
}

TEST(EventSphereTriangle, VertexHitUnderGravity) {
    // Dropped from rest straight above a vertex, outside the face's region: |p - vertex| = R
    // when the fall is h - R, h the height of the centre above the vertex.
    const Rotated tri = edge_and_vertex_case(1, Vec3(0, 0, 0), Vec3(-0.01, -0.005, -0.004), Vec3(-0.01, 0.005, -0.004));
    const double h = 0.03;
    const Trajectory path{Vec3(0, 0, h), Vec3::Zero(), kToiGravity, 0.0};
    TriangleContact contact;
    ASSERT_EQ(sphere_triangle_toi(path, kR, tri.corner[0], tri.corner[1], tri.corner[2], 0.0, 1.0, contact), ToiStatus::impact);
    const double t = std::sqrt(2.0 * (h - kR) / kG);
    EXPECT_NEAR(contact.time, t, 1e-12 * t);
    EXPECT_EQ(contact.feature, TriangleFeature::vertex_b);
    EXPECT_NEAR((contact.normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);
}

TEST(EventSphereTriangle, GrazingTheFaceAtTheApexIsATouch) {
    // Thrown up under a ceiling so that the apex of the centre is exactly R below it: the gap
    // to the ceiling has a double root at the apex time vz / g.
    const double vz = 1.0, apex = vz * vz / (2.0 * kG);
    const double ceiling = apex + kR;
    const Vec3 a(-0.02, -0.02, ceiling), b(0.0, 0.02, ceiling), c(0.02, -0.02, ceiling);
    const Trajectory path{Vec3::Zero(), Vec3(0, 0, vz), kToiGravity, 0.0};
    TriangleContact contact;
    ASSERT_EQ(sphere_triangle_toi(path, kR, a, b, c, 0.0, 1.0, contact), ToiStatus::impact);
    EXPECT_NEAR(contact.time, vz / kG, 1e-12 * vz / kG);
    EXPECT_EQ(contact.feature, TriangleFeature::face);
    EXPECT_NEAR((contact.normal + Vec3::UnitZ()).norm(), 0.0, 1e-15);
    // 1 nm lower and it misses; 1 nm higher and it hits before the apex.
    const Vec3 down(0, 0, -1e-9);
    ASSERT_EQ(sphere_triangle_toi(path, kR, a - down, b - down, c - down, 0.0, 1.0, contact), ToiStatus::miss);
    ASSERT_EQ(sphere_triangle_toi(path, kR, a + down, b + down, c + down, 0.0, 1.0, contact), ToiStatus::impact);
    EXPECT_LT(contact.time, vz / kG);
    EXPECT_NEAR(contact.time, (vz - std::sqrt(2.0 * kG * 1e-9)) / kG, 1e-9);
}

TEST(EventSphereTriangle, GrazingAnEdgeIsATouch) {
    // No gravity; the centre moves along z at x = R, y = 0, past the edge on the y axis: the
    // distance to the edge is sqrt(R^2 + z^2), a touch at z = 0.
    const Vec3 a(0, 0.01, 0), b(0, -0.01, 0), c(-0.02, 0, 0);
    const double z0 = -0.004, v = 0.7;
    const Trajectory path{Vec3(kR, 0, z0), Vec3(0, 0, v), Vec3::Zero(), 0.0};
    TriangleContact contact;
    ASSERT_EQ(sphere_triangle_toi(path, kR, a, b, c, 0.0, 1.0, contact), ToiStatus::impact);
    EXPECT_NEAR(contact.time, -z0 / v, 1e-12 * (-z0 / v));
    EXPECT_EQ(contact.feature, TriangleFeature::edge_ab);
    EXPECT_NEAR((contact.normal - Vec3::UnitX()).norm(), 0.0, 1e-12);
    // Just wide of the edge: no contact.
    const Trajectory wide{Vec3(kR * (1 + 1e-7), 0, z0), Vec3(0, 0, v), Vec3::Zero(), 0.0};
    EXPECT_EQ(sphere_triangle_toi(wide, kR, a, b, c, 0.0, 1.0, contact), ToiStatus::miss);
}

TEST(EventSphereTriangle, NoRedetectionRightAfterABounce) {
    // The state the engine leaves after a bounce on the floor: gap ~ 0 (an ulp either side),
    // moving away. The next contact is the return under gravity, at 2 vz / g, not t_begin.
    const Floor f;
    const double vz = 0.5;
    for (double gap : {0.0, -1e-12 * kR, 1e-12 * kR, -1e-16, 1e-16}) {
        const Trajectory path{Vec3(0.004, 0.001, kR + gap), Vec3(0.03, -0.02, vz), kToiGravity, 2.0};
        TriangleContact contact;
        ASSERT_EQ(sphere_triangle_toi(path, kR, f.a, f.b, f.c, 2.0, 3.0, contact), ToiStatus::impact) << gap;
        const double back = (vz + std::sqrt(vz * vz + 2.0 * kG * gap)) / kG;
        EXPECT_NEAR(contact.time - 2.0, back, 1e-12 * back) << gap;
        // Without gravity it never comes back.
        const Trajectory away{path.p0, path.v0, Vec3::Zero(), 2.0};
        EXPECT_EQ(sphere_triangle_toi(away, kR, f.a, f.b, f.c, 2.0, 3.0, contact), ToiStatus::miss) << gap;
    }
    // The same at an edge: touching the edge and moving away from it.
    const Vec3 a(0, 0.01, 0), b(0, -0.01, 0), c(-0.02, 0, 0);
    const Trajectory leaving{Vec3(kR * 0.6, 0, kR * 0.8), Vec3(0.6, 0.1, 0.8), Vec3::Zero(), 0.0};
    TriangleContact contact;
    EXPECT_EQ(sphere_triangle_toi(leaving, kR, a, b, c, 0.0, 1.0, contact), ToiStatus::miss);
}

TEST(EventSphereTriangle, TouchingWhileApproachingIsAnImpactNow) {
    const Floor f;
    for (double gap : {0.0, -1e-12 * kR}) {
        const Trajectory path{Vec3(0, 0, kR + gap), Vec3(0.1, 0, -0.5), kToiGravity, 1.0};
        TriangleContact contact;
        ASSERT_EQ(sphere_triangle_toi(path, kR, f.a, f.b, f.c, 1.0, 2.0, contact), ToiStatus::impact);
        EXPECT_NEAR(contact.time, 1.0, 1e-15);
        EXPECT_EQ(contact.feature, TriangleFeature::face);
    }
    // Resting (no normal velocity) but pulled in by gravity: in contact now.
    const Trajectory resting{Vec3(0, 0, kR), Vec3(0.1, 0, 0), kToiGravity, 1.0};
    TriangleContact contact;
    ASSERT_EQ(sphere_triangle_toi(resting, kR, f.a, f.b, f.c, 1.0, 2.0, contact), ToiStatus::impact);
    EXPECT_EQ(contact.time, 1.0);
}

TEST(EventSphereTriangle, OverlapAtTheStartIsReportedAsSuch) {
    const Floor f;
    const Trajectory deep{Vec3(0.001, 0, 0.5 * kR), Vec3(0, 0, -1), kToiGravity, 0.0};
    TriangleContact contact;
    ASSERT_EQ(sphere_triangle_toi(deep, kR, f.a, f.b, f.c, 0.0, 1.0, contact), ToiStatus::overlapping);
    EXPECT_EQ(contact.time, 0.0);
    EXPECT_EQ(contact.feature, TriangleFeature::face);
    EXPECT_NEAR((contact.normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);
    // Moving away does not make an overlap any less of one.
    const Trajectory leaving{Vec3(0.001, 0, -0.5 * kR), Vec3(0, 0, -1), kToiGravity, 0.0};
    ASSERT_EQ(sphere_triangle_toi(leaving, kR, f.a, f.b, f.c, 0.0, 1.0, contact), ToiStatus::overlapping);
    EXPECT_NEAR((contact.normal + Vec3::UnitZ()).norm(), 0.0, 1e-12);
    // Overlapping an edge from outside the face.
    const Trajectory edge{Vec3(0.02 - 0.3 * kR, -0.02 - 0.5 * kR, 0.0), Vec3(1, 0, 0), kToiGravity, 0.0};
    ASSERT_EQ(sphere_triangle_toi(edge, kR, f.a, f.b, f.c, 0.0, 1.0, contact), ToiStatus::overlapping);
    EXPECT_EQ(contact.feature, TriangleFeature::edge_ab);
    // A 1e-6 R overlap is an overlap; a 1e-12 R one is a touch.
    const Trajectory slight{Vec3(0, 0, kR * (1 - 1e-6)), Vec3(0, 0, 1), kToiGravity, 0.0};
    EXPECT_EQ(sphere_triangle_toi(slight, kR, f.a, f.b, f.c, 0.0, 1.0, contact), ToiStatus::overlapping);
}

TEST(EventSphereTriangle, DegenerateTrianglesActAsSegmentsAndPoints) {
    // A triangle collapsed to a segment along y (no face): hit on its edge at (d - R) / v.
    const double d = 0.01, v = 2.0;
    const Trajectory path{Vec3(d, 0.001, 0), Vec3(-v, 0, 0), Vec3::Zero(), 0.0};
    TriangleContact contact;
    ASSERT_EQ(sphere_triangle_toi(path, kR, Vec3(0, -0.01, 0), Vec3(0, 0.01, 0), Vec3(0, 0.002, 0), 0.0, 1.0, contact), ToiStatus::impact);
    EXPECT_NEAR(contact.time, (d - kR) / v, 1e-12 * (d - kR) / v);
    EXPECT_NE(contact.feature, TriangleFeature::face);
    EXPECT_NEAR((contact.point - Vec3(0, 0.001, 0)).norm(), 0.0, 1e-15);
    // Collapsed to a point: a vertex hit.
    const Trajectory at_point{Vec3(d, 0, 0), Vec3(-v, 0, 0), Vec3::Zero(), 0.0};
    const Vec3 o = Vec3::Zero();
    ASSERT_EQ(sphere_triangle_toi(at_point, kR, o, o, o, 0.0, 1.0, contact), ToiStatus::impact);
    EXPECT_NEAR(contact.time, (d - kR) / v, 1e-12 * (d - kR) / v);
    EXPECT_NEAR((contact.normal - Vec3::UnitX()).norm(), 0.0, 1e-12);
}

TEST(EventSphereTriangle, SearchAloneStartsWhereTheCallerSays) {
    // sphere_triangle_first_touch does not read the start state: from a point clear of the
    // triangle it finds the same contact as the full query; an empty window finds nothing.
    const Floor f;
    const Trajectory path{Vec3(0.001, 0.0, 0.02 + kR), Vec3::Zero(), kToiGravity, 0.0};
    TriangleContact full, search;
    ASSERT_EQ(sphere_triangle_toi(path, kR, f.a, f.b, f.c, 0.0, 1.0, full), ToiStatus::impact);
    ASSERT_TRUE(sphere_triangle_first_touch(path, kR, f.a, f.b, f.c, 0.03, 1.0, search));
    EXPECT_NEAR(search.time, full.time, 1e-15);
    EXPECT_FALSE(sphere_triangle_first_touch(path, kR, f.a, f.b, f.c, 0.03, 0.02, search));
    EXPECT_FALSE(sphere_triangle_first_touch(path, kR, f.a, f.b, f.c, 0.0, 0.05, search));  // ends before
}

TEST(EventSphereTriangle, RandomPathsAgreeWithDenseSampling) {
    // Random triangles of 0.5-5 mm and random parabolas through their neighbourhood. A reported
    // impact must be at gap 0, approaching or tangent, with no sample before it inside R; a miss
    // must have no sample inside R.
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto random_vec = [&](double s) -> Vec3 { return Vec3(unit(rng), unit(rng), unit(rng)) * s; };
    int impacts = 0, misses = 0, by_feature[7] = {0, 0, 0, 0, 0, 0, 0};
    constexpr int kSamples = 4000;
    for (int trial = 0; trial < 3000; ++trial) {
        const double size = 0.5e-3 + 4.5e-3 * 0.5 * (unit(rng) + 1.0);
        const Vec3 a = random_vec(size), b = random_vec(size), c = random_vec(size);
        const Vec3 start = random_vec(6e-3);
        const Vec3 g = trial % 3 == 0 ? Vec3::Zero() : Vec3(random_vec(1.0).normalized() * kG);
        const Vec3 aim = random_vec(2e-3) - start;  // towards the triangle, give or take
        const Trajectory path{start, aim.normalized() * (0.2 + 2.0 * 0.5 * (unit(rng) + 1.0)), g, 0.1 * unit(rng)};
        const double t_begin = path.t0 + 1e-3 * unit(rng), t_end = t_begin + 0.01;
        if (distance_to_triangle(path.position(t_begin), a, b, c) <= kR * 1.001) continue;
        TriangleContact contact;
        const ToiStatus s = sphere_triangle_toi(path, kR, a, b, c, t_begin, t_end, contact);
        ASSERT_NE(s, ToiStatus::overlapping);
        const double until = s == ToiStatus::impact ? contact.time : t_end;
        double min_gap = 1.0;
        for (int i = 0; i < kSamples; ++i) {
            const double t = t_begin + (until - t_begin) * i / kSamples;
            min_gap = std::min(min_gap, distance_to_triangle(path.position(t), a, b, c) - kR);
        }
        ASSERT_GT(min_gap, -1e-9 * kR) << "contact missed or reported late, trial " << trial;
        if (s == ToiStatus::miss) {
            EXPECT_GT(distance_to_triangle(path.position(t_end), a, b, c), kR * (1 - 1e-9));
            ++misses;
            continue;
        }
        ++impacts;
        ++by_feature[static_cast<int>(contact.feature)];
        const Vec3 p = path.position(contact.time);
        const ClosestPoint closest = closest_point_on_triangle(p, a, b, c);
        EXPECT_NEAR((p - closest.point).norm(), kR, 1e-12) << trial;
        EXPECT_NEAR((contact.point - closest.point).norm(), 0.0, 1e-12) << trial;
        EXPECT_NEAR((contact.normal - (p - contact.point) / kR).norm(), 0.0, 1e-9) << trial;
        EXPECT_LE(contact.normal.dot(path.velocity(contact.time)), 1e-9) << "separating at the contact, trial " << trial;
    }
    EXPECT_GT(impacts, 500);
    EXPECT_GT(misses, 200);
    for (int f = 0; f < 7; ++f) EXPECT_GT(by_feature[f], 10) << "feature " << f;
}

}  // namespace
}  // namespace peensim
