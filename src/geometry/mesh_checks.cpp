#include "geometry/mesh_checks.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace peensim {

namespace {

Vec3 doubled_area_vector(const TriangleMesh& mesh, std::size_t t) {
    const Vec3& a = mesh.corner(t, 0);
    return (mesh.corner(t, 1) - a).cross(mesh.corner(t, 2) - a);
}

}  // namespace

Vec3 triangle_normal(const TriangleMesh& mesh, std::size_t t) {
    const Vec3 n = doubled_area_vector(mesh, t);
    const double length = n.norm();
    return length > 0.0 ? Vec3(n / length) : Vec3(Vec3::Zero());
}

double triangle_area(const TriangleMesh& mesh, std::size_t t) { return 0.5 * doubled_area_vector(mesh, t).norm(); }

int triangle_edge_at(const TriangleMesh& mesh, std::size_t t, const Vec3& p) {
    double longest = 0.0, nearest = std::numeric_limits<double>::infinity();  // m2
    int edge = -1;
    for (int k = 0; k < 3; ++k) {
        const Vec3 a = mesh.corner(t, k), ab = mesh.corner(t, (k + 1) % 3) - a;
        const double length2 = ab.squaredNorm();
        longest = std::max(longest, length2);
        const double u = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
        const double d2 = (p - (a + u * ab)).squaredNorm();
        if (d2 < nearest) nearest = d2, edge = k;
    }
    return nearest <= 1e-12 * longest ? edge : -1;
}

double surface_area(const TriangleMesh& mesh) {
    double area = 0.0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) area += triangle_area(mesh, t);
    return area;
}

double enclosed_volume(const TriangleMesh& mesh) {
    if (mesh.triangle_count() == 0) return 0.0;
    // Tetrahedra from a point near the mesh rather than the origin: the result is the same for
    // a closed mesh, with less cancellation when the mesh sits far from the origin.
    const Bounds box = bounds(mesh);
    const Vec3 apex = 0.5 * (box.min_m + box.max_m);
    double six_volume = 0.0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const Vec3 a = mesh.corner(t, 0) - apex;
        const Vec3 b = mesh.corner(t, 1) - apex;
        const Vec3 c = mesh.corner(t, 2) - apex;
        six_volume += a.dot(b.cross(c));
    }
    return six_volume / 6.0;
}

EdgeReport edge_report(const TriangleMesh& mesh) {
    // One word per triangle side: the undirected edge (lower vertex index in the top 31 bits,
    // higher one below it) and, in the lowest bit, whether the side runs from lower to higher.
    // Sorting plain words groups the uses of each edge together.
    std::vector<std::uint64_t> sides;
    sides.reserve(3 * mesh.triangle_count());
    for (const auto& tri : mesh.triangles) {
        for (std::size_t k = 0; k < 3; ++k) {
            const auto from = static_cast<std::uint64_t>(tri[k]);
            const auto to = static_cast<std::uint64_t>(tri[(k + 1) % 3]);
            const std::uint64_t ascending = from < to ? 1 : 0;
            sides.push_back((std::min(from, to) << 33) | (std::max(from, to) << 1) | ascending);
        }
    }
    std::sort(sides.begin(), sides.end());

    EdgeReport report;
    for (std::size_t first = 0; first < sides.size();) {
        const std::uint64_t edge = sides[first] >> 1;
        std::size_t last = first + 1;
        while (last < sides.size() && (sides[last] >> 1) == edge) ++last;
        const std::size_t uses = last - first;
        ++report.edges;
        if (uses == 1) ++report.boundary_edges;
        if (uses > 2) ++report.non_manifold_edges;
        if (uses == 2 && (sides[first] & 1U) == (sides[first + 1] & 1U)) ++report.misoriented_edges;
        first = last;
    }
    return report;
}

bool is_closed(const TriangleMesh& mesh) { return edge_report(mesh).closed(); }

Bounds bounds(const TriangleMesh& mesh) {
    Bounds box;
    if (mesh.triangle_count() == 0) return box;
    box.min_m = box.max_m = mesh.corner(0, 0);
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        for (int k = 0; k < 3; ++k) {
            box.min_m = box.min_m.cwiseMin(mesh.corner(t, k));
            box.max_m = box.max_m.cwiseMax(mesh.corner(t, k));
        }
    }
    return box;
}

}  // namespace peensim
