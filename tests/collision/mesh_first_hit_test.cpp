// MeshCollider::first_hit, the time-ordered swept-sphere walk of the BVH, against the brute-force
// loop over every triangle with the same exact kernel: random throws, starts right after a bounce
// and starts touching a surface, on a box and on a fine cylinder. Then the cost: leaves visited
// per query on a coarse (~5k) and a fine (~500k) cylinder, which must stay small and nearly flat.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "collision/mesh_collider.h"
#include "geometry/box_mesh.h"
#include "geometry/cylinder_mesh.h"

namespace peensim {
namespace {

constexpr double kR = 1e-3;  // m, shot radius

struct Reference {
    ToiStatus status = ToiStatus::miss;
    int triangle = -1;
    TriangleContact contact;
};

// The earliest contact over all triangles, with the kernel's own semantics.
Reference brute_force(const TriangleMesh& mesh, const Trajectory& path, double t_begin, double t_end) {
    Reference best;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        TriangleContact c;
        const ToiStatus s = sphere_triangle_toi(path, kR, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2), t_begin, t_end, c);
        if (s == ToiStatus::overlapping) return {s, static_cast<int>(t), c};
        if (s == ToiStatus::impact && (best.status == ToiStatus::miss || c.time < best.contact.time)) best = {s, static_cast<int>(t), c};
    }
    return best;
}

double distance_to(const TriangleMesh& mesh, int t, const Vec3& p) {
    const auto tt = static_cast<std::size_t>(t);
    return (p - closest_point_on_triangle(p, mesh.corner(tt, 0), mesh.corner(tt, 1), mesh.corner(tt, 2)).point).norm();
}

struct Query {
    Trajectory path;
    double t_begin, t_end;
};

// Throws at the mesh from around it and from inside its bounds, starts just after a bounce off a
// random triangle (separating), and starts touching one while approaching; some of those on an
// edge or a vertex shared with neighbours.
std::vector<Query> random_queries(const TriangleMesh& mesh, int count, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), u01(0.0, 1.0);
    auto random_vec = [&]() -> Vec3 { return Vec3(unit(rng), unit(rng), unit(rng)); };
    Vec3 lo = mesh.vertices[0], hi = mesh.vertices[0];
    for (const Vec3& v : mesh.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const Vec3 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    std::vector<Query> out;
    for (int i = 0; i < count; ++i) {
        const Vec3 g = i % 4 == 0 ? Vec3(random_vec().normalized() * 9.81) : (i % 4 == 1 ? Vec3::Zero() : Vec3(0, 0, -9.81));
        const double t0 = unit(rng), t_begin = t0 + 0.002 * unit(rng);
        const double speed = 0.3 + 3.0 * u01(rng);
        Vec3 start, velocity;
        if (i % 5 < 3) {
            start = centre + (half + Vec3::Constant(0.005)).cwiseProduct(random_vec());
            const Vec3 aim = centre + half.cwiseProduct(random_vec()) - start;
            velocity = aim.normalized() * speed;
        } else {
            const auto t = static_cast<std::size_t>(u01(rng) * static_cast<double>(mesh.triangle_count() - 1));
            double wa = u01(rng), wb = u01(rng);
            if (wa + wb > 1.0) {
                wa = 1.0 - wa;
                wb = 1.0 - wb;
            }
            if (i % 3 == 0) wb = 0.0;       // on an edge, shared with a neighbour
            if (i % 7 == 0) wa = wb = 0.0;  // on a vertex
            const Vec3 a = mesh.corner(t, 0), b = mesh.corner(t, 1), c = mesh.corner(t, 2);
            const Vec3 n = (b - a).cross(c - a).normalized() * (unit(rng) < 0.0 ? -1.0 : 1.0);
            start = a + wa * (b - a) + wb * (c - a) + n * kR;
            velocity = random_vec().normalized() * speed;
            const bool separating = i % 5 == 3;
            if ((velocity.dot(n) > 0.0) != separating) velocity -= 2.0 * velocity.dot(n) * n;
        }
        // Described from t0, starting at t_begin where the sphere is at `start`.
        const Trajectory at_begin{start, velocity, g, t_begin};
        out.push_back({at_begin.rebased(t0), t_begin, t_begin + 0.02});
    }
    return out;
}

struct Agreement {
    int impacts = 0, misses = 0, overlaps = 0, other_triangle = 0;
    double leaves = 0.0;
};

Agreement compare_with_brute_force(const TriangleMesh& mesh, const std::vector<Query>& queries) {
    const MeshCollider collider(mesh);
    Agreement a;
    for (std::size_t q = 0; q < queries.size(); ++q) {
        const Query& query = queries[q];
        const Reference want = brute_force(mesh, query.path, query.t_begin, query.t_end);
        MeshCollider::Hit hit;
        MeshCollider::SweepCounters counters;
        const ToiStatus got = collider.first_hit(query.path, kR, query.t_begin, query.t_end, hit, counters);
        a.leaves += static_cast<double>(counters.leaves_visited);
        EXPECT_EQ(got, want.status) << "query " << q;
        if (got != want.status) continue;
        if (got == ToiStatus::miss) {
            ++a.misses;
            continue;
        }
        if (got == ToiStatus::overlapping) {
            ++a.overlaps;
            EXPECT_LT(distance_to(mesh, hit.triangle, query.path.position(query.t_begin)), kR) << "query " << q;
            continue;
        }
        ++a.impacts;
        const double scale = query.t_end - query.t_begin;
        EXPECT_NEAR(hit.contact.time, want.contact.time, 1e-12 * scale) << "query " << q;
        if (hit.triangle != want.triangle) {
            // Another triangle touched at the same moment (a shared edge or vertex).
            ++a.other_triangle;
            EXPECT_NEAR(distance_to(mesh, hit.triangle, query.path.position(hit.contact.time)), kR, 1e-9 * kR) << "query " << q;
        } else {
            EXPECT_EQ(hit.contact.feature, want.contact.feature) << "query " << q;
            EXPECT_NEAR((hit.contact.point - want.contact.point).norm(), 0.0, 1e-12) << "query " << q;
        }
    }
    a.leaves /= static_cast<double>(queries.size());
    return a;
}

TEST(EventMeshFirstHit, BoxMatchesBruteForce) {
    BoxSpec spec;
    spec.size_m = Vec3(0.02, 0.03, 0.015);
    spec.center_m = Vec3(0.001, -0.002, 0.003);
    spec.divisions = Eigen::Vector3i(6, 5, 4);
    const TriangleMesh mesh = box(spec);
    const Agreement a = compare_with_brute_force(mesh, random_queries(mesh, 2000, 1));
    std::cout << "[ box      ] " << mesh.triangle_count() << " triangles: " << a.impacts << " impacts (" << a.other_triangle
              << " on an equally near triangle), " << a.misses << " misses, " << a.overlaps << " overlaps; " << a.leaves
              << " leaves per query\n";
    EXPECT_GT(a.impacts, 1000);
    EXPECT_GT(a.misses, 50);
}

TEST(EventMeshFirstHit, FineCylinderMatchesBruteForce) {
    CylinderSpec spec;
    spec.radius_m = 0.01;
    spec.height_m = 0.03;
    spec.segments = 400;
    spec.axial_subdivisions = 20;
    spec.cap_rings = 4;
    spec.axis = Axis::y;
    spec.center_m = Vec3(0.002, 0.0, -0.001);
    const TriangleMesh mesh = cylinder(spec);
    const Agreement a = compare_with_brute_force(mesh, random_queries(mesh, 1200, 2));
    std::cout << "[ cylinder ] " << mesh.triangle_count() << " triangles: " << a.impacts << " impacts (" << a.other_triangle
              << " on an equally near triangle), " << a.misses << " misses, " << a.overlaps << " overlaps; " << a.leaves
              << " leaves per query\n";
    EXPECT_GT(a.impacts, 800);
    EXPECT_GT(a.misses, 50);
}

TEST(EventMeshFirstHit, OverlapAndMissAreReported) {
    BoxSpec spec;
    spec.size_m = Vec3(0.02, 0.02, 0.02);
    const TriangleMesh mesh = box(spec);
    const MeshCollider collider(mesh);
    MeshCollider::Hit hit;
    MeshCollider::SweepCounters counters;
    // Centre half a radius outside the +z face: overlapping, whatever the motion.
    const Trajectory overlapping{Vec3(0.003, 0.002, 0.01 + 0.5 * kR), Vec3(0, 0, 1), Vec3(0, 0, -9.81), 0.0};
    ASSERT_EQ(collider.first_hit(overlapping, kR, 0.0, 0.1, hit, counters), ToiStatus::overlapping);
    EXPECT_EQ(hit.contact.time, 0.0);
    EXPECT_NEAR((hit.contact.normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);
    // Thrown away from the box without gravity: nothing to hit, and the walk stops at the root.
    const Trajectory away{Vec3(0, 0, 0.02), Vec3(0.1, 0.2, 1.0), Vec3::Zero(), 0.0};
    counters = {};
    EXPECT_EQ(collider.first_hit(away, kR, 0.0, 1.0, hit, counters), ToiStatus::miss);
    EXPECT_EQ(counters.leaves_visited, 0u);
    // Dropped on the top face: the free-fall time, the face's normal.
    const double h = 0.05;
    const Trajectory drop{Vec3(0.004, -0.003, 0.01 + kR + h), Vec3::Zero(), Vec3(0, 0, -9.81), 0.0};
    ASSERT_EQ(collider.first_hit(drop, kR, 0.0, 1.0, hit, counters), ToiStatus::impact);
    EXPECT_NEAR(hit.contact.time, std::sqrt(2 * h / 9.81), 1e-12 * std::sqrt(2 * h / 9.81));
    EXPECT_NEAR((hit.contact.normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);
    EXPECT_EQ(mesh.group_names[static_cast<std::size_t>(mesh.group_of_triangle[static_cast<std::size_t>(hit.triangle)])], "+z");
}

TEST(EventMeshFirstHit, SkimmingAFinePlateStaysExact) {
    // A sphere gliding 1e-4 R above a finely divided plate touches nothing, yet every leaf along
    // its path is within reach of it; pulled down gently, it lands where brute force says.
    BoxSpec spec;
    spec.size_m = Vec3(0.04, 0.04, 0.002);
    spec.divisions = Eigen::Vector3i(200, 200, 1);
    const TriangleMesh mesh = box(spec);
    const MeshCollider collider(mesh);
    MeshCollider::SweepCounters glide_counters;
    for (int i = 0; i < 8; ++i) {
        const double angle = 0.3 * i;
        const Trajectory glide{Vec3(-0.015 * std::cos(angle), -0.015 * std::sin(angle), 0.001 + kR * (1 + 1e-4)),
                               Vec3(std::cos(angle), std::sin(angle), 0.0), Vec3::Zero(), 0.0};
        MeshCollider::Hit hit;
        EXPECT_EQ(collider.first_hit(glide, kR, 0.0, 0.03, hit, glide_counters), ToiStatus::miss);
        EXPECT_EQ(brute_force(mesh, glide, 0.0, 0.03).status, ToiStatus::miss);
        // Pulled down at 1 m/s^2, it lands after sqrt(2 * 1e-7 m / 1 m/s^2), as brute force finds.
        const Trajectory dip{glide.p0, glide.v0, Vec3(0, 0, -1.0), 0.0};
        MeshCollider::SweepCounters counters;
        ASSERT_EQ(collider.first_hit(dip, kR, 0.0, 0.03, hit, counters), ToiStatus::impact);
        const Reference want_dip = brute_force(mesh, dip, 0.0, 0.03);
        ASSERT_EQ(want_dip.status, ToiStatus::impact);
        EXPECT_NEAR(hit.contact.time, want_dip.contact.time, 1e-15);
        // The 1e-7 m drop is a difference of millimetre heights: ~1e-12 relative rounding.
        EXPECT_NEAR(hit.contact.time, std::sqrt(2e-4 * kR), 1e-11 * std::sqrt(2e-4 * kR));
    }
    std::cout << "[ skim     ] " << mesh.triangle_count() << " triangles: a 30 mm glide without contact visits "
              << static_cast<double>(glide_counters.leaves_visited) / 8 << " leaves\n";
}

// The cylinder of the cost test (r 10 mm, 30 mm long, axis z) at a given tessellation; built once.
const TriangleMesh& cost_cylinder(bool fine) {
    auto make = [](int segments, int axial) {
        CylinderSpec spec;
        spec.radius_m = 0.01;
        spec.height_m = 0.03;
        spec.segments = segments;
        spec.axial_subdivisions = axial;
        return cylinder(spec);
    };
    static const TriangleMesh coarse = make(100, 24);       // 5 000 triangles
    static const TriangleMesh fine_mesh = make(2000, 124);  // 500 000 triangles
    return fine ? fine_mesh : coarse;
}

// Throws of 1-5 m/s under gravity from up to 25 mm away at the cylinder, over 30 ms.
std::vector<Query> long_throws(int count) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), u01(0.0, 1.0);
    std::vector<Query> queries;
    for (int i = 0; i < count; ++i) {
        Vec3 start;
        do {
            start = Vec3(unit(rng), unit(rng), unit(rng)) * 0.025;
        } while (Vec3(start.x(), start.y(), 0).norm() < 0.012 && std::fabs(start.z()) < 0.017);
        const Vec3 aim = Vec3(0.008 * unit(rng), 0.008 * unit(rng), 0.014 * unit(rng)) - start;
        queries.push_back({Trajectory{start, aim.normalized() * (1.0 + 4.0 * u01(rng)), Vec3(0, 0, -9.81), 0.0}, 0.0, 0.03});
    }
    return queries;
}

// Shot 1-4 mm off the wall in random directions at 0.5-5 m/s over 2 ms: the short horizons of
// an event-driven step (the next cell crossing is ~2R away).
std::vector<Query> near_wall_steps(int count) {
    std::mt19937_64 rng(6);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), u01(0.0, 1.0);
    std::vector<Query> queries;
    for (int i = 0; i < count; ++i) {
        const double phi = 3.14159 * unit(rng), r = 0.011 + 0.003 * u01(rng), z = 0.013 * unit(rng);
        const Vec3 start(r * std::cos(phi), r * std::sin(phi), z);
        const Vec3 direction = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
        queries.push_back({Trajectory{start, direction * (0.5 + 4.5 * u01(rng)), Vec3(0, 0, -9.81), 0.0}, 0.0, 0.002});
    }
    return queries;
}

TEST(EventMeshFirstHit, AFullQueueKeepsTheAnswerExact) {
    // With the queue cut to 2 entries, nearly every push overflows into the depth-first walk of
    // that subtree: the answers must stay those of the full queue and of brute force.
    const TriangleMesh& mesh = cost_cylinder(false);
    const MeshCollider collider(mesh);
    const std::vector<Query> queries = long_throws(300);
    MeshCollider::SweepCounters small_counters, full_counters;
    for (const Query& q : queries) {
        MeshCollider::Hit small, full;
        const ToiStatus s = collider.first_hit(q.path, kR, q.t_begin, q.t_end, small, small_counters, 2);
        ASSERT_EQ(s, collider.first_hit(q.path, kR, q.t_begin, q.t_end, full, full_counters));
        if (s != ToiStatus::impact) continue;
        EXPECT_NEAR(small.contact.time, full.contact.time, 1e-12 * q.t_end);  // leaves searched over other spans: rounding
        const Reference want = brute_force(mesh, q.path, q.t_begin, q.t_end);
        EXPECT_NEAR(small.contact.time, want.contact.time, 1e-12 * q.t_end);
    }
    EXPECT_GT(small_counters.heap_overflows, 100u);
    EXPECT_EQ(full_counters.heap_overflows, 0u);
}

TEST(EventMeshFirstHit, FineCylinderLongThrowsMatchBruteForce) {
    // On 500k triangles: the long throws land where a loop over every triangle says.
    const TriangleMesh& mesh = cost_cylinder(true);
    const std::vector<Query> queries = long_throws(40);
    const MeshCollider collider(mesh);
    MeshCollider::SweepCounters counters;
    for (const Query& q : queries) {
        MeshCollider::Hit hit;
        ASSERT_EQ(collider.first_hit(q.path, kR, q.t_begin, q.t_end, hit, counters), ToiStatus::impact);
    }
    const Agreement a = compare_with_brute_force(mesh, queries);
    EXPECT_EQ(a.impacts, 40);
}

TEST(EventMeshFirstHit, LeavesVisitedStayFlatFromCoarseToFineMesh) {
    // The same cylinder at ~5k and ~500k triangles; prints leaves, nodes and boxes per query and
    // the time per query (not asserted: the machine is shared).
    for (const bool short_steps : {false, true}) {
        double leaves_per_query[2] = {0.0, 0.0};
        for (const bool fine : {false, true}) {
            const TriangleMesh& mesh = cost_cylinder(fine);
            const MeshCollider collider(mesh);
            const std::vector<Query> queries = short_steps ? near_wall_steps(50000) : long_throws(20000);
            MeshCollider::SweepCounters counters;
            int hits = 0;
            const auto t_start = std::chrono::steady_clock::now();
            for (const Query& q : queries) {
                MeshCollider::Hit hit;
                hits += collider.first_hit(q.path, kR, q.t_begin, q.t_end, hit, counters) == ToiStatus::impact;
            }
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
            const double n = static_cast<double>(queries.size());
            leaves_per_query[fine] = static_cast<double>(counters.leaves_visited) / n;
            std::cout << "[ cost     ] " << (short_steps ? "2 ms steps near the wall, " : "30 ms throws, ") << mesh.triangle_count()
                      << " triangles: " << hits << " of " << queries.size() << " hit; per query " << leaves_per_query[fine] << " leaves, "
                      << static_cast<double>(counters.nodes_visited) / n << " nodes, " << static_cast<double>(counters.boxes_tested) / n
                      << " boxes, " << 1e9 * seconds / n << " ns; " << counters.heap_overflows << " queue overflows\n";
            EXPECT_GT(hits, short_steps ? 10000 : 19000);
        }
        EXPECT_LT(leaves_per_query[0], 50.0);
        EXPECT_LT(leaves_per_query[1], 50.0);
    }
}

}  // namespace
}  // namespace peensim
