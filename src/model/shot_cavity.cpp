#include "model/shot_cavity.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "common/input_error.h"

namespace peensim {

namespace {

constexpr double kProbeClearance = 0.01;  // -, gap left between a probed shot and surfaces, fraction of R

SonotrodeFaces upward_faces(const Component& sonotrode, const Vec3& up) {
    SonotrodeFaces s;
    const Pose pose = sonotrode.kinematics.pose(SimTime{});
    double total = 0.0;
    for (std::size_t t = 0; t < sonotrode.mesh->triangle_count(); ++t) {
        const std::array<Vec3, 3> w{pose.to_world(sonotrode.mesh->corner(t, 0)), pose.to_world(sonotrode.mesh->corner(t, 1)),
                                    pose.to_world(sonotrode.mesh->corner(t, 2))};
        const Vec3 n2a = (w[1] - w[0]).cross(w[2] - w[0]);
        if (n2a.norm() == 0.0 || n2a.normalized().dot(up) < 0.9) continue;
        total += 0.5 * n2a.norm();
        s.faces.push_back(w);
        s.cumulative_area.push_back(total);
    }
    return s;
}

// True if the ray from p (world) along `dir` meets any component: p lies under a roof, so it
// belongs inside the chamber; if the enclosure says it is outside, the chamber leaks.
bool has_roof(const Model& model, const Vec3& p, const Vec3& dir, std::vector<int>& scratch) {
    const double length = (model.world_hi - model.world_lo).norm();
    for (const Component& c : model.components) {
        const Pose pose = c.kinematics.pose(SimTime{});
        const Vec3 o = pose.to_component(p), d = pose.rotation.transpose() * dir;
        const Vec3 end = o + d * length;
        c.collider->triangles_overlapping(o.cwiseMin(end), o.cwiseMax(end), scratch);
        for (int t : scratch) {
            const auto tt = static_cast<std::size_t>(t);
            // Moller-Trumbore ray-triangle intersection.
            const Vec3 a = c.mesh->corner(tt, 0), e1 = c.mesh->corner(tt, 1) - a, e2 = c.mesh->corner(tt, 2) - a;
            const Vec3 h = d.cross(e2);
            const double det = e1.dot(h);
            if (std::abs(det) < 1e-300) continue;
            const Vec3 sv = o - a;
            const double u = sv.dot(h) / det;
            if (u < 0.0 || u > 1.0) continue;
            const Vec3 q = sv.cross(e1);
            const double v = d.dot(q) / det;
            if (v < 0.0 || u + v > 1.0) continue;
            if (e2.dot(q) / det > 0.0) return true;
        }
    }
    return false;
}

TriangleMesh world_mesh(const Model& model) {
    TriangleMesh all;
    for (const Component& c : model.components) {
        const Pose pose = c.kinematics.pose(SimTime{});
        const int base = static_cast<int>(all.vertices.size());
        for (const Vec3& v : c.mesh->vertices) all.vertices.push_back(pose.to_world(v));
        for (const auto& t : c.mesh->triangles) all.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    }
    return all;
}

// Closed-chamber check: a point on the sonotrode with something above it (under the chamber's
// roof) must be enclosed; if it is not, the chamber leaks. Points with nothing above them lie
// beyond the chamber (a horn wider than the chamber) and are simply not used for placement.
void require_closed_chamber(const Model& model, const Enclosure& enclosure, const SonotrodeFaces& faces, const Vec3& up, Random& rng) {
    const SceneDescription& scene = model.description;
    const double R = model.max_shot_radius_m;  // where a shot of any size of the mix fits (as placement)
    const SourceLocation sono_where = scene.components[static_cast<std::size_t>(model.sonotrode)].where;
    std::vector<int> scratch;
    int roofed = 0, unread = 0;
    std::vector<Vec3> covered_face;  // face points under a roof where no shot of radius R fits
    for (int k = 0; k < 256 && roofed < 64; ++k) {
        const Vec3 face = faces.sample(rng);
        const Vec3 p = face + up * (R * (1.0 + kProbeClearance));
        // Only points where a shot fits (a point hugging a wall may sit in a cell the walls mark).
        if (!clear_of_meshes(model, p, R) || !has_roof(model, p, up, scratch)) {
            if (covered_face.size() < 64 && has_roof(model, face + up * (kProbeClearance * R), up, scratch)) covered_face.push_back(face);
            continue;
        }
        // A point in a pocket finer than the grid proves nothing either way (the grid cannot
        // tell whether it leaks): only points it reads count.
        if (!enclosure.reads(p)) {
            ++unread;
            continue;
        }
        ++roofed;
        if (enclosure.inside(p)) continue;
        Vec3 lo = Vec3::Constant(1e300), hi = -lo;
        for (const Component& c : model.components)
            if (c.role == ComponentRole::chamber) {
                lo = lo.cwiseMin(c.world_lo);
                hi = hi.cwiseMax(c.world_hi);
            }
        Vec3 where = p;
        enclosure.escape_point(p, lo, hi, where);
        SourceLocation at{scene.source_file, 0, 0};
        for (const ComponentDesc& c : scene.components)
            if (c.role == ComponentRole::chamber) {
                at = c.where;
                break;
            }
        throw InputError(at, "components",
                         "the chamber is not closed around the sonotrode: a shot placed on the sonotrode at " + mm_point(p) +
                             " can leave the assembly near " + mm_point(where) +
                             " (expected chamber, sonotrode, parts and fixtures to enclose the shot)");
    }
    if (roofed == 0 && !covered_face.empty()) {
        // A chamber is there, but the shot fits nowhere under it (or under the parts over the
        // face): say so, with the largest shot that would (bisection on the radius at each covered
        // face point).
        double widest = 0.0;  // m, radius
        for (const Vec3& face : covered_face) {
            double lo = widest, hi = R;
            if (!clear_of_meshes(model, face + up * (lo * (1.0 + kProbeClearance)), lo)) continue;
            for (int i = 0; i < 40; ++i) {
                const double mid = 0.5 * (lo + hi);
                (clear_of_meshes(model, face + up * (mid * (1.0 + kProbeClearance)), mid) ? lo : hi) = mid;
            }
            widest = std::max(widest, lo);
        }
        std::ostringstream s;
        s.precision(3);
        s << "the shot (" << 2e3 * R << " mm) does not fit anywhere over the sonotrode's upper face: the widest room there fits a shot of "
          << 2e3 * widest << " mm, under the parts and the chamber (expected shot smaller than the gaps over the sonotrode)";
        throw InputError(scene.shot.where, scene.shot.sizes_given ? "shot.sizes" : "shot.diameter", s.str());
    }
    if (roofed == 0 && unread > 0) {
        std::ostringstream s;
        s.precision(3);
        s << "the room over the sonotrode is everywhere narrower than the closed-chamber check resolves (cells of "
          << 1e3 * enclosure.cell_size() << " mm for this assembly's size; expected gaps over the sonotrode at least a cell wide)";
        throw InputError(sono_where, "components", s.str());
    }
    if (roofed == 0)
        throw InputError(sono_where, "components", "expected a chamber above the sonotrode, found nothing above its upper face");
}

// The enclosed region the shot start in: the one most points of the first layer on the sonotrode
// lie in. Above the first layer, a point may lie inside a closed part (a rod hanging over the
// sonotrode) or a sealed pocket, which the enclosure also counts as enclosed: such a shot would
// start inside the part. Sampled with its own generator, so the placement's draws are unchanged.
int cavity_region(const Model& model, Enclosure& enclosure, const SonotrodeFaces& faces, const Vec3& up) {
    const double R = model.max_shot_radius_m;  // where a shot of any size of the mix fits (as placement)
    Random probe(model.seed ^ 0x9e3779b97f4a7c15ULL);
    std::unordered_map<int, int> votes;
    for (int k = 0; k < 256; ++k) {
        const Vec3 p = faces.sample(probe) + up * (R * (1.0 + kProbeClearance));
        const int region = enclosure.region(p);
        if (region >= 0 && clear_of_meshes(model, p, R)) ++votes[region];
    }
    int best = -1, most = 0;
    for (const auto& [region, n] : votes)
        if (n > most || (n == most && region < best)) best = region, most = n;
    return best;
}

}  // namespace

Vec3 SonotrodeFaces::sample(Random& rng) const {
    const double u = rng.uniform() * cumulative_area.back();
    const std::size_t f =
        static_cast<std::size_t>(std::upper_bound(cumulative_area.begin(), cumulative_area.end(), u) - cumulative_area.begin());
    const auto& tri = faces[std::min(f, faces.size() - 1)];
    const double r1 = std::sqrt(rng.uniform()), r2 = rng.uniform();
    return (1.0 - r1) * tri[0] + r1 * (1.0 - r2) * tri[1] + r1 * r2 * tri[2];
}

// Exact clearance of a sphere of radius r at p (world) from every component at t = 0.
bool clear_of_meshes(const Model& model, const Vec3& p, double r) {
    const SimTime t0;
    for (const Component& c : model.components) {
        const Vec3 q = c.kinematics.pose(t0).to_component(p);
        MeshCollider::Closest closest;
        MeshCollider::QueryCounters counters;
        if (c.collider->closest_within(q, r, closest, counters)) return false;
    }
    return true;
}

double distance_to(const Component& c, const Vec3& p, double within) {
    MeshCollider::Closest closest;
    MeshCollider::QueryCounters counters;
    return c.collider->closest_within(c.kinematics.pose(SimTime{}).to_component(p), within, closest, counters)
               ? std::min(within, closest.distance)
               : within;
}

double clearance(const Model& model, const Vec3& p, double within) {
    double nearest = within;
    for (const Component& c : model.components) nearest = distance_to(c, p, nearest);
    return nearest;
}

std::string mm_point(const Vec3& p) {
    std::ostringstream s;
    s.precision(4);
    s << "(" << p.x() * 1e3 << ", " << p.y() * 1e3 << ", " << p.z() * 1e3 << ") mm";
    return s.str();
}

std::string component_field(std::size_t i) { return "components[" + std::to_string(i) + "]"; }

Vec3 sonotrode_up(const Model& model) {
    const Vec3 up = model.gravity_m_per_s2.norm() > 0.0 ? Vec3(-model.gravity_m_per_s2.normalized()) : Vec3::UnitZ();
    const Vec3 axis = model.sonotrode_component().kinematics.axis;
    return axis.dot(up) >= 0.0 ? axis : Vec3(-axis);
}

ShotCavity::ShotCavity(const Model& model, Random& rng)
    : model_(model),
      up_(sonotrode_up(model)),
      faces_(upward_faces(model.sonotrode_component(), up_)),
      enclosure_(world_mesh(model), 0.5 * model.min_shot_radius_m, model.min_shot_radius_m,  // openings the smallest shot passes
                 [&model](const Vec3& p, double within) { return clearance(model, p, within); }) {
    const SceneDescription& scene = model.description;
    if (faces_.faces.empty())
        throw InputError(scene.components[static_cast<std::size_t>(model.sonotrode)].where,
                         component_field(static_cast<std::size_t>(model.sonotrode)) + ".mesh",
                         "expected the sonotrode mesh to have an upper face pointing into the chamber (against gravity), found none");
    require_closed_chamber(model, enclosure_, faces_, up_, rng);
    region_ = cavity_region(model, enclosure_, faces_, up_);
}

bool ShotCavity::contains(const Vec3& p) const { return enclosure_.in_region(p, region_); }

}  // namespace peensim
