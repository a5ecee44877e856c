#include "model/assembly_checks.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <utility>

#include "common/parallel_chunks.h"
#include "common/random.h"
#include "geometry/mesh_checks.h"
#include "model/facet_reach.h"

namespace peensim {

namespace {

// A length for a message: mm, 3 significant digits.
std::string mm_text(double m) {
    std::ostringstream s;
    s.precision(3);
    s << m * 1e3 << " mm";
    return s.str();
}

constexpr double kTouch = 1e-7;           // m: surfaces this close (float STL rounding) touch, they do not cross
constexpr int kReachSamples = 1500;       // surface points per component for the reach test
constexpr int kMaxSubdivision = 64;       // per triangle edge, when sampling surfaces for the sweep test
constexpr int kMaxSweepBins = 4096;       // axial bins of a rotating part's (r, z) profile
constexpr std::size_t kCheckChunks = 32;  // of a mesh's triangles or vertices, each checked on one core

bool is_solid_role(ComponentRole r) { return r == ComponentRole::part || r == ComponentRole::fixture || r == ComponentRole::almen; }

std::string label(const Model& m, std::size_t i) { return component_field(i) + " (" + m.components[i].name + ")"; }

// World corners of triangle t of component c in its rest pose at t = 0 (plus `offset`, m).
std::array<Vec3, 3> world_triangle(const Component& c, const Pose& pose, std::size_t t, const Vec3& offset) {
    return {pose.to_world(c.mesh->corner(t, 0)) + offset, pose.to_world(c.mesh->corner(t, 1)) + offset,
            pose.to_world(c.mesh->corner(t, 2)) + offset};
}

// Where the segment [p, q] crosses triangle (a, b, c) strictly (its ends on opposite sides, each
// farther than kTouch from the plane), if it does.
bool segment_crosses(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& at) {
    const Vec3 n2 = (b - a).cross(c - a);
    const double area2 = n2.norm();
    if (!(area2 > 0.0)) return false;
    const Vec3 n = n2 / area2;
    const double dp = n.dot(p - a), dq = n.dot(q - a);
    if (!((dp > kTouch && dq < -kTouch) || (dp < -kTouch && dq > kTouch))) return false;
    const Vec3 x = p + (q - p) * (dp / (dp - dq));
    // Inside the triangle, farther than kTouch from its edges: a segment through an edge or a corner
    // only touches (the rod's end rim lying on the chamber wall).
    const double u = n.dot((b - a).cross(x - a)), v = n.dot((c - b).cross(x - b)), w = n.dot((a - c).cross(x - c));
    if (u <= kTouch * (b - a).norm() || v <= kTouch * (c - b).norm() || w <= kTouch * (a - c).norm()) return false;
    at = x;
    return true;
}

// An edge of `a` (offset by oa) crossing a face of `b` (offset by ob), world frame at t = 0.
// The first crossing in a's triangle order, as one pass over them would find it: the triangles in
// kCheckChunks chunks on every core, the first chunk with a crossing taken (the chunks after one
// that found a crossing are not begun).
bool edges_cross_faces(const Component& a, const Vec3& oa, const Component& b, const Vec3& ob, Vec3& at) {
    const Pose pa = a.kinematics.pose(SimTime{}), pb = b.kinematics.pose(SimTime{});
    // b's faces lie within its world bounds: a triangle of a wholly outside them (by more than a
    // touch) has no edge that can cross one, and is not looked up in b's BVH (on a 500k-triangle
    // gear beside its axle, most are not).
    const Vec3 b_lo = b.world_lo + ob - Vec3::Constant(kTouch), b_hi = b.world_hi + ob + Vec3::Constant(kTouch);
    std::vector<std::optional<Vec3>> crossing(kCheckChunks);
    std::atomic<std::size_t> first_found{kCheckChunks};
    for_each_chunk(kCheckChunks, [&](std::size_t chunk) {
        if (chunk > first_found.load()) return;
        std::vector<int> near;
        const auto [first, end] = chunk_range(a.mesh->triangle_count(), kCheckChunks, chunk);
        for (std::size_t t = first; t < end; ++t) {
            const std::array<Vec3, 3> w = world_triangle(a, pa, t, oa);
            if ((w[0].cwiseMax(w[1]).cwiseMax(w[2]).array() < b_lo.array()).any() ||
                (w[0].cwiseMin(w[1]).cwiseMin(w[2]).array() > b_hi.array()).any())
                continue;
            for (int k = 0; k < 3; ++k) {
                // In b's frame, so b's BVH finds the faces near the edge.
                const Vec3 p = pb.to_component(w[static_cast<std::size_t>(k)] - ob),
                           q = pb.to_component(w[static_cast<std::size_t>((k + 1) % 3)] - ob);
                b.collider->triangles_overlapping(p.cwiseMin(q) - Vec3::Constant(kTouch), p.cwiseMax(q) + Vec3::Constant(kTouch), near);
                for (int f : near) {
                    const auto ft = static_cast<std::size_t>(f);
                    Vec3 x;
                    if (segment_crosses(p, q, b.mesh->corner(ft, 0), b.mesh->corner(ft, 1), b.mesh->corner(ft, 2), x)) {
                        crossing[chunk] = pb.to_world(x) + ob;
                        for (std::size_t seen = first_found.load(); chunk < seen && !first_found.compare_exchange_weak(seen, chunk);) {}
                        return;
                    }
                }
            }
        }
    });
    for (const std::optional<Vec3>& x : crossing)
        if (x) {
            at = *x;
            return true;
        }
    return false;
}

bool meshes_cross(const Component& a, const Vec3& oa, const Component& b, const Vec3& ob, Vec3& at) {
    if ((a.world_hi.array() + oa.array() < b.world_lo.array() + ob.array() - kTouch).any() ||
        (b.world_hi.array() + ob.array() < a.world_lo.array() + oa.array() - kTouch).any())
        return false;
    return edges_cross_faces(a, oa, b, ob, at) || edges_cross_faces(b, ob, a, oa, at);
}

// Points on a triangle no farther than `spacing` apart (corners included), at most kMaxSubdivision
// per edge.
template <class Visit>
void sample_triangle(const Vec3& a, const Vec3& b, const Vec3& c, double spacing, Visit&& visit) {
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int n = std::clamp(static_cast<int>(std::ceil(longest / spacing)), 1, kMaxSubdivision);
    for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j) visit(a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n));
}

// Nearest distance between the vertices of one and the surface of the other, both ways (m).
// Each vertex's distance is exact whatever bound it was asked within, so the least of them is the
// same found chunk by chunk on every core. The least so far is shared: each query is bounded by it
// (a chunk far from `b` bounded by its own least alone searched far more of b's BVH).
double vertex_clearance(const Component& a, const Component& b, double within) {
    std::atomic<double> best{within};
    for (const auto* pair : {&a, &b}) {
        const Component& from = *pair;
        const Component& to = pair == &a ? b : a;
        const Pose pose = from.kinematics.pose(SimTime{});
        const std::vector<Vec3>& vertices = from.mesh->vertices;
        for_each_chunk(kCheckChunks, [&](std::size_t chunk) {
            const auto [first, end] = chunk_range(vertices.size(), kCheckChunks, chunk);
            for (std::size_t v = first; v < end; ++v) {
                double seen = best.load(std::memory_order_relaxed);
                const double d = distance_to(to, pose.to_world(vertices[v]), seen);
                while (d < seen && !best.compare_exchange_weak(seen, d, std::memory_order_relaxed)) {}
            }
        });
    }
    return best.load();
}

// Fraction of c's surface with room for a shot centre beside it, in the cavity.
double reachable_fraction(const Model& m, std::size_t ci, ShotCavity& cavity) {
    const Component& c = m.components[ci];
    const Pose pose = c.kinematics.pose(SimTime{});
    std::vector<double> cumulative;
    double total = 0.0;
    for (std::size_t t = 0; t < c.mesh->triangle_count(); ++t) cumulative.push_back(total += triangle_area(*c.mesh, t));
    if (!(total > 0.0)) return 0.0;
    Random rng(0x5eed + ci);
    const double R = m.min_shot_radius_m;  // the smallest shot of a mix reaches furthest
    int reachable = 0;
    for (int k = 0; k < kReachSamples; ++k) {
        const double u = rng.uniform() * total;
        const auto t = static_cast<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin());
        const std::size_t tt = std::min(t, c.mesh->triangle_count() - 1);
        const std::array<Vec3, 3> w = world_triangle(c, pose, tt, Vec3::Zero());
        const double r1 = std::sqrt(rng.uniform()), r2 = rng.uniform();
        const Vec3 x = (1.0 - r1) * w[0] + r1 * (1.0 - r2) * w[1] + r1 * r2 * w[2];
        const Vec3 n = (w[1] - w[0]).cross(w[2] - w[0]).normalized();
        reachable += shot_fits_beside(m, &cavity, c, x, n, R) ? 1 : 0;
    }
    return static_cast<double>(reachable) / kReachSamples;
}

// A boundary edge (used by one triangle) of a mesh: its vertices and that triangle.
struct BoundaryEdge {
    int a = 0, b = 0;
    std::size_t triangle = 0;
};

std::vector<BoundaryEdge> boundary_edges(const TriangleMesh& mesh) {
    std::map<std::pair<int, int>, std::pair<int, std::size_t>> uses;  // edge -> (uses, a triangle)
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
        for (int k = 0; k < 3; ++k) {
            const int a = mesh.triangles[t][static_cast<std::size_t>(k)], b = mesh.triangles[t][static_cast<std::size_t>((k + 1) % 3)];
            auto& [n, triangle] = uses[{std::min(a, b), std::max(a, b)}];
            ++n;
            triangle = t;
        }
    std::vector<BoundaryEdge> out;
    for (const auto& [edge, use] : uses)
        if (use.first == 1) out.push_back({edge.first, edge.second, use.second});
    return out;
}

// A point of an opening of c with room for a shot beside it: no other component within a shot
// diameter of the edge, and a shot centre in the chamber's cavity clear of every surface next to
// it (off its triangle either way, or over the opening). The edge's own point lies on the surface,
// where the cavity cannot say which side it is on: a hole in a shaft's wall was never found so.
bool exposed_opening(const Model& m, std::size_t ci, ShotCavity& cavity, Vec3& at, std::size_t& edges) {
    const Component& c = m.components[ci];
    if (c.edges.boundary_edges == 0) return false;  // closed: no opening (and no map of its edges)
    const std::vector<BoundaryEdge> open = boundary_edges(*c.mesh);
    edges = open.size();
    if (open.empty()) return false;
    const Pose pose = c.kinematics.pose(SimTime{});
    const double R = m.min_shot_radius_m, D = 2.0 * R;  // the smallest shot of a mix passes the narrowest gaps
    for (const BoundaryEdge& e : open) {
        const Vec3 p = pose.to_world(c.mesh->vertices[static_cast<std::size_t>(e.a)]);
        const Vec3 q = pose.to_world(c.mesh->vertices[static_cast<std::size_t>(e.b)]);
        const Vec3 normal = pose.rotation * triangle_normal(*c.mesh, e.triangle);
        const Vec3 over = normal.cross(q - p).normalized();  // in the triangle's plane, across the edge
        const int n = std::clamp(static_cast<int>(std::ceil((q - p).norm() / R)), 1, kMaxSubdivision);
        for (int k = 0; k <= n; ++k) {
            const Vec3 x = p + (q - p) * (double(k) / n);
            bool sealed = false;
            for (std::size_t j = 0; j < m.components.size() && !sealed; ++j)
                if (j != ci && distance_to(m.components[j], x, D) < D) sealed = true;
            if (sealed || !(shot_fits_beside(m, &cavity, c, x, normal, R) || shot_fits_beside(m, &cavity, c, x, over, R))) continue;
            at = x;
            return true;
        }
    }
    return false;
}

// A rotating part's (r, z) profile about its axis: per axial bin, the smallest and largest radius
// of its surface. Turned a full turn, it is the volume the part sweeps.
struct SweptProfile {
    Vec3 point, axis;
    double z0 = 0.0, bin = 1.0;
    double z_lo = 0.0, z_hi = 0.0;  // m, the part's axial extent: a face lying on its end planes only touches
    std::vector<double> r_min, r_max;

    std::pair<double, double> rz(const Vec3& x) const {
        const Vec3 d = x - point;
        const double z = d.dot(axis);
        return {(d - z * axis).norm(), z};
    }
    // True if x (world) lies strictly inside the swept volume.
    bool sweeps(const Vec3& x) const {
        const auto [r, z] = rz(x);
        if (!(z > z_lo + kTouch && z < z_hi - kTouch)) return false;
        const double k = std::floor((z - z0) / bin);
        if (k < 0.0 || k >= static_cast<double>(r_min.size())) return false;
        const auto i = static_cast<std::size_t>(k);
        return r > r_min[i] + kTouch && r < r_max[i] - kTouch;
    }
};

SweptProfile swept_profile(const Component& c, double spacing) {
    SweptProfile s;
    s.point = c.kinematics.axis_point_m;
    s.axis = c.kinematics.axis_direction.normalized();
    const Pose pose = c.kinematics.pose(SimTime{});
    double lo = 1e300, hi = -1e300;
    for (const Vec3& v : c.mesh->vertices) {
        const double z = (pose.to_world(v) - s.point).dot(s.axis);
        lo = std::min(lo, z);
        hi = std::max(hi, z);
    }
    s.bin = std::max(spacing, (hi - lo) / kMaxSweepBins);
    s.z0 = lo;
    s.z_lo = lo;
    s.z_hi = hi;
    const auto bins = static_cast<std::size_t>(std::floor((hi - lo) / s.bin)) + 1;
    s.r_min.assign(bins, 1e300);
    s.r_max.assign(bins, -1e300);
    for (std::size_t t = 0; t < c.mesh->triangle_count(); ++t) {
        const std::array<Vec3, 3> w = world_triangle(c, pose, t, Vec3::Zero());
        sample_triangle(w[0], w[1], w[2], s.bin, [&](const Vec3& x) {
            const auto [r, z] = s.rz(x);
            const auto i = std::min(bins - 1, static_cast<std::size_t>(std::max(0.0, std::floor((z - s.z0) / s.bin))));
            s.r_min[i] = std::min(s.r_min[i], r);
            s.r_max[i] = std::max(s.r_max[i], r);
        });
    }
    return s;
}

// A point of fixed component f (offset by `offset`) inside the volume swept by the profile.
bool hits_swept(const Component& f, const Vec3& offset, const SweptProfile& s, const Vec3& swept_lo, const Vec3& swept_hi, Vec3& at) {
    const Pose pose = f.kinematics.pose(SimTime{});
    // f's triangles near the swept box: the box's corners in f's frame bound them.
    Vec3 lo = Vec3::Constant(1e300), hi = -lo;
    for (int k = 0; k < 8; ++k) {
        const Vec3 corner((k & 1) ? swept_hi.x() : swept_lo.x(), (k & 2) ? swept_hi.y() : swept_lo.y(),
                          (k & 4) ? swept_hi.z() : swept_lo.z());
        const Vec3 local = pose.to_component(corner - offset);
        lo = lo.cwiseMin(local);
        hi = hi.cwiseMax(local);
    }
    std::vector<int> near;
    f.collider->triangles_overlapping(lo, hi, near);
    bool found = false;
    for (int t : near) {
        const std::array<Vec3, 3> w = world_triangle(f, pose, static_cast<std::size_t>(t), offset);
        sample_triangle(w[0], w[1], w[2], s.bin, [&](const Vec3& x) {
            if (!found && s.sweeps(x)) {
                found = true;
                at = x;
            }
        });
        if (found) return true;
    }
    return false;
}

void add(AssemblyReport& r, const Model& m, std::size_t i, bool error, std::string field_suffix, std::string message,
         std::optional<Vec3> at = std::nullopt) {
    // Named as the user knows it: the field path says where in the file, the name which part.
    const ComponentDesc& d = m.description.components[i];
    r.issues.push_back(
        {error, d.where, component_field(i) + field_suffix, std::string(role_name(d.role)) + " '" + d.name + "': " + message, at});
}

// The mesh's bounds as placed at t = 0, and a turning part's swept solid's: a vertex at radius rho
// from the axis (unit u) sweeps a circle that reaches rho sqrt(1 - u_k^2) either way along world
// axis k from its centre.
void rest_and_swept_bounds(const Component& c, ComponentFacts& facts) {
    const Pose pose = c.kinematics.rest;
    const bool turning = c.kinematics.kind == Kinematics::Kind::rotating;
    const Vec3& p = c.kinematics.axis_point_m;
    const Vec3& u = c.kinematics.axis_direction;
    const Vec3 reach = (Vec3::Ones() - u.cwiseProduct(u)).cwiseMax(0.0).cwiseSqrt();
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo, swept_lo = lo, swept_hi = hi;
    double radius = 0.0;
    for (const Vec3& v : c.mesh->vertices) {
        const Vec3 w = pose.to_world(v);
        lo = lo.cwiseMin(w), hi = hi.cwiseMax(w);
        if (!turning) continue;
        const Vec3 centre = p + u.dot(w - p) * u;
        const double rho = (w - centre).norm();
        radius = std::max(radius, rho);
        swept_lo = swept_lo.cwiseMin(centre - rho * reach), swept_hi = swept_hi.cwiseMax(centre + rho * reach);
    }
    facts.rest_lo = lo, facts.rest_hi = hi;
    if (turning) facts.swept_lo = swept_lo, facts.swept_hi = swept_hi, facts.swept_radius_m = radius;
}

}  // namespace

std::size_t AssemblyReport::errors() const {
    return static_cast<std::size_t>(std::count_if(issues.begin(), issues.end(), [](const AssemblyIssue& i) { return i.error; }));
}

std::size_t AssemblyReport::warnings() const { return issues.size() - errors(); }

AssemblyReport check_assembly(const Model& m, ShotCavity* cavity) {
    AssemblyReport report;
    const std::size_t n = m.components.size();
    // Every sonotrode (none in a scene fed by sources alone; then there is no cavity either, and
    // the shot's reach is not checked), and how far each travels (m, its +A0 offset).
    std::vector<std::size_t> sonotrodes;
    for (std::size_t k = 0; k < n; ++k)
        if (m.components[k].role == ComponentRole::sonotrode) sonotrodes.push_back(k);
    const auto travel_of = [](const Component& c) {
        return c.role == ComponentRole::sonotrode ? Vec3(c.kinematics.axis.normalized() * c.kinematics.amplitude_m) : Vec3(Vec3::Zero());
    };
    const double diagonal = (m.world_hi - m.world_lo).norm();
    const double R = m.min_shot_radius_m;  // the smallest shot of a mix reaches furthest

    for (std::size_t i = 0; i < n; ++i) {
        const Component& c = m.components[i];
        ComponentFacts facts;
        facts.lo = c.world_lo;
        facts.hi = c.world_hi;
        rest_and_swept_bounds(c, facts);
        facts.triangles = c.mesh->triangle_count();
        facts.closed = c.edges.closed();
        if (c.mesh->dropped_degenerate_facets > 0)
            add(report, m, i, false, ".mesh",
                std::to_string(c.mesh->dropped_degenerate_facets) + " facets of zero area dropped (" +
                    std::to_string(c.mesh->triangle_count()) + " kept): check the mesh export");
        if (is_solid_role(c.role)) {
            for (std::size_t k : sonotrodes) {
                const Component& sono = m.components[k];
                const double clearance = vertex_clearance(c, sono, diagonal) - sono.kinematics.amplitude_m;
                if (!(facts.clearance_to_sonotrode_m <= clearance)) facts.clearance_to_sonotrode_m = clearance;
            }
            double to_chamber = diagonal;
            for (const Component& k : m.components)
                if (k.role == ComponentRole::chamber) to_chamber = std::min(to_chamber, vertex_clearance(c, k, to_chamber));
            facts.clearance_to_chamber_m = to_chamber;
            if (cavity) facts.reachable_fraction = reachable_fraction(m, i, *cavity);
        }
        report.components.push_back(facts);
    }

    for (std::size_t i = 0; i < n; ++i) {
        const Component& c = m.components[i];
        if (!is_solid_role(c.role)) continue;
        const ComponentFacts& facts = report.components[i];
        std::ostringstream where;
        where.precision(4);
        where << "it spans " << mm_point(c.world_lo) << " to " << mm_point(c.world_hi);
        if (cavity && facts.reachable_fraction < kMinReachable) {
            std::ostringstream s;
            s.precision(3);
            s << (facts.reachable_fraction == 0.0
                      ? "no part"
                      : "only " + std::to_string(static_cast<int>(std::round(100.0 * facts.reachable_fraction))) + " %")
              << " of its surface can be reached by the shot";
            // The shot wider than the gaps around the part is the likelier cause than a misplaced
            // part: name it with the gaps.
            const double diameter = 2.0 * m.max_shot_radius_m;  // m
            const bool sono_gap = diameter > facts.clearance_to_sonotrode_m,
                       chamber_gap =
                           facts.clearance_to_chamber_m > 0.0 && diameter > facts.clearance_to_chamber_m;  // 0: held by the chamber
            if (sono_gap || chamber_gap) {
                s << ": the shot (" << 1e3 * diameter << " mm) is wider than the gap between it and the "
                  << (sono_gap ? "sonotrode (" + mm_text(facts.clearance_to_sonotrode_m) + ")" : "")
                  << (sono_gap && chamber_gap ? " and the " : "")
                  << (chamber_gap ? "chamber (" + mm_text(facts.clearance_to_chamber_m) + ")" : "")
                  << "; expected shot that pass between them: a smaller shot.diameter, or the part further from them";
            } else {
                s << " (the rest lies outside the chamber's cavity, in the sonotrode or in another component); " << where.str()
                  << ": check its translation, rotation and mesh_unit";
            }
            add(report, m, i, true, "", s.str());
        }
        Vec3 at;
        for (std::size_t k : sonotrodes) {
            const Component& sono = m.components[k];
            const Vec3 travel = travel_of(sono);
            for (const Vec3& offset : {Vec3(Vec3::Zero()), Vec3(travel), Vec3(-travel)})
                if (meshes_cross(c, Vec3::Zero(), sono, offset, at)) {
                    add(report, m, i, true, "",
                        "intersects the sonotrode" + std::string(sonotrodes.size() > 1 ? " " + label(m, k) : "") +
                            std::string(offset.isZero() ? "" : " within its vibration travel (+-A0)") + " near " + mm_point(at) + "; " +
                            where.str() + ": move it clear of the sonotrode's face",
                        at);
                    break;
                }
        }
        for (std::size_t j = i + 1; j < n; ++j)
            if (is_solid_role(m.components[j].role) && meshes_cross(c, Vec3::Zero(), m.components[j], Vec3::Zero(), at))
                add(report, m, i, true, "", "intersects " + label(m, j) + " near " + mm_point(at) + ": components may touch, not overlap",
                    at);
        for (std::size_t j = 0; j < n; ++j)
            if (m.components[j].role == ComponentRole::chamber && meshes_cross(c, Vec3::Zero(), m.components[j], Vec3::Zero(), at))
                add(report, m, i, false, "",
                    "passes through the wall of " + label(m, j) + " near " + mm_point(at) +
                        " (a shaft through a wall is a real design; if this part was meant to be inside, check its placement)",
                    at);
        std::size_t open_edges = 0;
        if (cavity && exposed_opening(m, i, *cavity, at, open_edges))
            add(report, m, i, true, ".mesh",
                "the mesh is open (" + std::to_string(open_edges) + " boundary edges) and shot can reach an opening near " + mm_point(at) +
                    ": close the mesh (a missing cap?) or seal the opening against a wall",
                at);
        if (c.kinematics.kind == Kinematics::Kind::rotating && c.kinematics.omega_rad_per_s != 0.0) {
            const SweptProfile profile = swept_profile(c, 0.5 * R);
            for (std::size_t j = 0; j < n; ++j) {
                const Component& f = m.components[j];
                if (j == i || f.kinematics.kind == Kinematics::Kind::rotating) continue;
                bool hit = false;
                const Vec3 travel = travel_of(f);  // zero but for a sonotrode
                for (const Vec3& offset : {Vec3(Vec3::Zero()), Vec3(travel), Vec3(-travel)}) {
                    if (f.role != ComponentRole::sonotrode && !offset.isZero()) continue;
                    if (hits_swept(f, offset, profile, c.world_lo, c.world_hi, at)) {
                        hit = true;
                        break;
                    }
                }
                if (hit)
                    add(report, m, i, true, ".motion",
                        "turning, it sweeps through " + label(m, j) + " near " + mm_point(at) + " (axis through " +
                            mm_point(c.kinematics.axis_point_m) + "): check motion.axis_point and axis_direction",
                        at);
            }
        }
    }
    return report;
}

}  // namespace peensim
