#include "model/facet_reach.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>

#include "geometry/mesh_checks.h"
#include "geometry/triangle_sampling.h"

namespace peensim {

namespace {

constexpr double kClearanceFactor = 1.05;  // -, the probe centre's distance from the surface in shot radii

// shot_fits_beside with `clear(centre, k)` deciding whether a shot centred at `centre` on side k
// (0: along n, 1: against it) touches no component.
template <class Clear>
bool fits_beside(ShotCavity* cavity, const Component& c, const Vec3& x, const Vec3& n, double R, Clear&& clear) {
    for (int k = 0; k < 2; ++k) {
        if (k == 1 && c.solid) break;  // a solid's outside is the side its normals point to
        const Vec3 centre = x + (k == 0 ? 1.0 : -1.0) * kClearanceFactor * R * n;
        if ((cavity == nullptr || cavity->contains(centre)) && clear(centre, k)) return true;
    }
    return false;
}

}  // namespace

bool shot_fits_beside(const Model& model, ShotCavity* cavity, const Component& c, const Vec3& x, const Vec3& n, double R) {
    return fits_beside(cavity, c, x, n, R, [&](const Vec3& centre, int) { return clear_of_meshes(model, centre, R); });
}

std::vector<double> reachable_fractions(const Model& model, std::size_t ci, ShotCavity* cavity) {
    const Component& c = model.components[ci];
    const Pose pose = c.kinematics.pose(SimTime{});
    const double R = model.min_shot_radius_m;  // the smallest shot of a mix reaches furthest
    const TriangleMesh& mesh = *c.mesh;
    std::vector<double> reach(mesh.triangle_count(), 0.0);
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const double probes =
            std::clamp(std::ceil(triangle_area(mesh, t) / (4.0 * R * R)), 1.0, 1.0 * kReachProbesPerEdge * kReachProbesPerEdge);
        const int n = static_cast<int>(std::ceil(std::sqrt(probes)));
        const Vec3 normal = pose.rotation * triangle_normal(mesh, t);
        int reached = 0, total = 0;
        for_each_sub_centroid(mesh, t, n, [&](const Vec3& p) {
            ++total;
            reached += shot_fits_beside(model, cavity, c, pose.to_world(p), normal, R) ? 1 : 0;
        });
        reach[t] = static_cast<double>(reached) / total;
    }
    return reach;
}

namespace {

// What reach_test keeps of its recent distance queries, on one thread: each shot centre queried,
// its answer, and how far (m) a centre may lie from it and still have that answer. The distance
// to the meshes changes by at most as much as the centre moves, so a centre within
// |clearance - R| of a queried one is clear of them, or not, as it was, whichever triangle or side
// of the surface it was probed for. Probes come in turn, each thread on triangles of its own, and
// a probe's neighbours were mostly probed a few queries before: the corners a triangle shares with
// the last few (on a fine mesh, nearly the same centre each time), and in a cell of probes that
// disagree, the samples away from where the answer flips. The shipped gear's 1.31 M tests asked
// 0.66 M queries keeping only the last answer per side, and 0.39 M keeping the last 8; the
// 500k-triangle gear's 2.26 M tests, 1.51 M and 0.50 M (docs/design.md, "Setup and analysis").
struct ReachAnchor {
    Vec3 centre = Vec3::Zero();  // m, world
    double holds_within_m = -1.0;
    bool clear = false;
};
struct ReachMemo {
    static constexpr int kAnchors = 8;  // more answer few more: 16 took 1.05 M of the fine gear's queries, 8 took 1.00 M
    std::uint64_t test = 0;             // which reach_test's
    double radius_m = 0.0;
    ReachAnchor recent[kAnchors];
    int next = 0;  // the slot the next query's anchor takes (the oldest)

    // The answer of an anchor that holds at `centre`, newest first: 1 clear, 0 not, -1 none holds.
    int answer_at(const Vec3& centre) const {
        for (int k = 1; k <= kAnchors; ++k) {
            const ReachAnchor& a = recent[(next - k + kAnchors) % kAnchors];
            if (a.holds_within_m > 0.0 && (centre - a.centre).squaredNorm() < a.holds_within_m * a.holds_within_m) return a.clear ? 1 : 0;
        }
        return -1;
    }
    void keep(const ReachAnchor& a) {
        recent[next] = a;
        next = (next + 1) % kAnchors;
    }
};

// Rounding of the distances (~1e-18 m at a part's size) is far below this margin, which is far
// below any shot: an answer taken from an anchor is the one a query would give.
constexpr double kAnchorSlack_m = 1e-9;
// How far beyond the shot radius a query looks for the clearance that lets neighbours share its
// answer: the nearest-first descent shrinks its reach to the nearest triangle found, so a wider
// start costs little.
constexpr double kAnchorReachFactor = 3.0;

// Whether a shot of radius R centred at `centre` (world, m) touches no component at t = 0: the
// answer of clear_of_meshes (shot_cavity.h), from a recent anchor when the centre lies within its
// reach; a query's own anchor joins the recent ones.
bool clear_of_meshes_near(const Model& model, const Component& own, const Vec3& centre, double R, ReachMemo& memo) {
    if (const int known = memo.answer_at(centre); known >= 0) return known == 1;
    ReachAnchor anchor;
    const SimTime t0;
    double nearest = kAnchorReachFactor * R;  // m: no component nearer so far
    // The probed part first: its own surface, about 1.05 R away, bounds the other queries at once.
    const auto blocks = [&](const Component& c) {
        const Vec3 q = c.kinematics.pose(t0).to_component(centre);
        MeshCollider::Closest closest;
        MeshCollider::QueryCounters counters;
        if (!c.collider->closest_within(q, nearest, closest, counters)) return false;
        // As clear_of_meshes's query of radius R decides: a triangle nearer than R, squared.
        const double d2 = (q - closest.point).squaredNorm();
        if (d2 < R * R) {
            anchor = {centre, R - std::sqrt(d2) - kAnchorSlack_m, false};
            return true;
        }
        nearest = std::min(nearest, closest.distance);
        return false;
    };
    const bool blocked = blocks(own) || std::any_of(model.components.begin(), model.components.end(),
                                                    [&](const Component& c) { return &c != &own && blocks(c); });
    if (!blocked) anchor = {centre, nearest - R - kAnchorSlack_m, true};
    memo.keep(anchor);
    return !blocked;
}

}  // namespace

std::function<bool(const Vec3&, std::size_t, double)> reach_test(const Model& model, std::size_t ci, ShotCavity* cavity) {
    const Component& c = model.components[ci];
    const Pose pose = c.kinematics.pose(SimTime{});
    static std::atomic<std::uint64_t> tests{0};
    const std::uint64_t id = ++tests;  // this test's anchors are its own
    return [&model, &c, cavity, pose, id](const Vec3& p, std::size_t t, double R) {
        // This thread's anchors, kept from triangle to triangle (an anchor holds for any centre
        // near it, and the triangles come in turn, each thread on triangles of its own).
        thread_local ReachMemo memo;
        if (memo.test != id || memo.radius_m != R) {
            memo = ReachMemo{};
            memo.test = id;
            memo.radius_m = R;
        }
        // As shot_fits_beside, with the anchors.
        return fits_beside(cavity, c, pose.to_world(p), pose.rotation * triangle_normal(*c.mesh, t), R,
                           [&](const Vec3& centre, int) { return clear_of_meshes_near(model, c, centre, R, memo); });
    };
}

}  // namespace peensim
