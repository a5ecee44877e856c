#include "render/map_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace peensim {

namespace {

constexpr double kSameFacing = 0.70710678118654752;  // cos 45 deg: neighbours whose value a corner takes

int subdivisions(const TriangleMesh& mesh, std::size_t t, double spacing_m) {
    const Vec3 &a = mesh.corner(t, 0), &b = mesh.corner(t, 1), &c = mesh.corner(t, 2);
    const double longest = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()});
    return std::max(1, static_cast<int>(std::ceil(longest / spacing_m)));
}

}  // namespace

MapMesh map_mesh(const TriangleMesh& mesh, std::span<const double> values, double spacing_m) {
    const std::size_t n_tri = mesh.triangle_count();
    if (values.size() != n_tri) throw std::invalid_argument("map_mesh: one value per triangle expected");
    if (!(spacing_m > 0.0)) throw std::invalid_argument("map_mesh: the spacing must be positive");
    std::vector<Vec3> normal(n_tri);
    std::vector<double> area(n_tri);
    for (std::size_t t = 0; t < n_tri; ++t) {
        const Vec3 cross = (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
        area[t] = 0.5 * cross.norm();
        normal[t] = area[t] > 0.0 ? Vec3(cross.normalized()) : Vec3::Zero();
    }
    // The triangles around each vertex (compressed rows).
    std::vector<std::size_t> start(mesh.vertices.size() + 1, 0), around(3 * n_tri);
    for (const auto& tri : mesh.triangles)
        for (int v : tri) ++start[static_cast<std::size_t>(v) + 1];
    for (std::size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < n_tri; ++t)
        for (int v : mesh.triangles[t]) around[fill[static_cast<std::size_t>(v)]++] = t;

    // The spacing: coarser while the sub-triangles would be too many.
    double spacing = spacing_m;
    for (;;) {
        std::size_t count = 0;
        for (std::size_t t = 0; t < n_tri; ++t) {
            const auto n = static_cast<std::size_t>(subdivisions(mesh, t, spacing));
            count += n * n;
        }
        if (count <= kMaxMapTriangles) break;
        spacing *= 1.25;
    }

    MapMesh out;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t t = 0; t < n_tri; ++t) {
        double corner[3];
        for (int k = 0; k < 3; ++k) {
            const auto v = static_cast<std::size_t>(mesh.triangles[t][static_cast<std::size_t>(k)]);
            double sum = 0.0, weight = 0.0;
            for (std::size_t i = start[v]; i < start[v + 1]; ++i) {
                const std::size_t u = around[i];
                if (!std::isfinite(values[u]) || normal[u].dot(normal[t]) < kSameFacing) continue;
                sum += area[u] * values[u];
                weight += area[u];
            }
            corner[k] = weight > 0.0 ? sum / weight : values[t];
        }
        const int n = subdivisions(mesh, t, spacing);
        const Vec3& a = mesh.corner(t, 0);
        const Vec3 u = (mesh.corner(t, 1) - a) / n, w = (mesh.corner(t, 2) - a) / n;
        // Grid points (i, j), i + j <= n, row by row.
        const int first = static_cast<int>(out.mesh.vertices.size());
        auto point = [&](int i, int j) { return first + j * (n + 1) - j * (j - 1) / 2 + i; };
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i + j <= n; ++i) out.mesh.vertices.push_back(a + i * u + j * w);
        auto value_at = [&](double fu, double fw) {  // fractions of the edges AB and AC; no data stays no data
            if (!std::isfinite(values[t])) return nan;
            const double x = (1.0 - fu - fw) * corner[0] + fu * corner[1] + fw * corner[2];
            return std::isfinite(x) ? x : values[t];
        };
        for (int j = 0; j < n; ++j)
            for (int i = 0; i + j < n; ++i) {
                out.mesh.triangles.push_back({point(i, j), point(i + 1, j), point(i, j + 1)});
                out.values.push_back(value_at((i + 1.0 / 3.0) / n, (j + 1.0 / 3.0) / n));
                if (i + j + 1 < n) {
                    out.mesh.triangles.push_back({point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)});
                    out.values.push_back(value_at((i + 2.0 / 3.0) / n, (j + 2.0 / 3.0) / n));
                }
            }
    }
    return out;
}

}  // namespace peensim
