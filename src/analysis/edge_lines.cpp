#include "analysis/edge_lines.h"

#include <cmath>
#include <map>
#include <stdexcept>

namespace peensim {

EdgeLines::EdgeLines(const TriangleMesh& mesh, std::span<const ForecastImpact> all, double grid_side_m) {
    // A segment is known by its two end points, in a fixed order: the triangles on both sides
    // of it find the same line whether or not the mesh shares their vertices.
    using Key = std::array<double, 6>;
    const auto key_of = [&](std::size_t t, int k, bool& flipped) {
        const Vec3& a = mesh.corner(t, k);
        const Vec3& b = mesh.corner(t, (k + 1) % 3);
        flipped = std::lexicographical_compare(b.data(), b.data() + 3, a.data(), a.data() + 3);
        const Vec3& p = flipped ? b : a;
        const Vec3& q = flipped ? a : b;
        return Key{p.x(), p.y(), p.z(), q.x(), q.y(), q.z()};
    };
    std::map<Key, std::int32_t> line_of;
    std::vector<std::vector<Impact>> per_line;
    for (const ForecastImpact& i : all) {
        if (i.edge < 0) continue;
        ++count;
        bool flipped = false;
        const Key key = key_of(i.triangle, i.edge, flipped);
        const auto [it, added] = line_of.try_emplace(key, static_cast<std::int32_t>(lines.size()));
        if (added) {
            Line l;
            l.start = Vec3(key[0], key[1], key[2]);
            const Vec3 d = Vec3(key[3], key[4], key[5]) - l.start;
            l.length_m = d.norm();
            l.along = l.length_m > 0.0 ? Vec3(d / l.length_m) : Vec3::UnitX();
            lines.push_back(l);
            per_line.emplace_back();
        }
        Line& l = lines[static_cast<std::size_t>(it->second)];
        const Vec3 p(i.point_m[0], i.point_m[1], i.point_m[2]);
        const double radius = std::sqrt(static_cast<double>(i.dent_area_m2) / M_PI);
        l.largest_radius_m = std::max(l.largest_radius_m, radius);
        per_line[static_cast<std::size_t>(it->second)].push_back(
            {std::clamp((p - l.start).dot(l.along), 0.0, l.length_m), radius, i.batch});
    }
    for (std::size_t k = 0; k < lines.size(); ++k) {
        std::vector<Impact>& v = per_line[k];
        std::sort(v.begin(), v.end(), [](const Impact& a, const Impact& b) { return a.s_m < b.s_m; });
        lines[k].first = impacts.size();
        lines[k].count = v.size();
        impacts.insert(impacts.end(), v.begin(), v.end());
    }
    if (lines.empty()) return;
    // A grid of cubes of side grid_side_m (at least the largest dent radius of any line) listing
    // the lines that pass within it: a sample finds every line whose dents can cover it in its cube.
    for (const Line& l : lines) reach_m = std::max(reach_m, l.largest_radius_m);
    if (!(reach_m <= grid_side_m)) throw std::invalid_argument("EdgeLines: the grid's side is less than the largest dent radius of a line");
    inverse_side_ = 1.0 / grid_side_m;
    std::vector<std::pair<std::uint64_t, std::int32_t>> keyed;
    for (std::size_t k = 0; k < lines.size(); ++k) {
        const Line& l = lines[k];
        const Vec3 end = l.start + l.length_m * l.along;
        const auto lo = cube_of(l.start.cwiseMin(end) - Vec3::Constant(l.largest_radius_m), inverse_side_);
        const auto hi = cube_of(l.start.cwiseMax(end) + Vec3::Constant(l.largest_radius_m), inverse_side_);
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
            for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
                for (std::int64_t x = lo[0]; x <= hi[0]; ++x) keyed.emplace_back(cube_key(x, y, z, -1), static_cast<std::int32_t>(k));
    }
    index_by_cube(keyed, grid_, grid_lines_);
    // The triangles some line passes near: their samples are placed one by one.
    near_triangle_.assign(mesh.triangle_count(), false);
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const Vec3 a = mesh.corner(t, 0), b = mesh.corner(t, 1), c = mesh.corner(t, 2);
        const auto lo = cube_of(a.cwiseMin(b).cwiseMin(c), inverse_side_);
        const auto hi = cube_of(a.cwiseMax(b).cwiseMax(c), inverse_side_);
        for (std::int64_t z = lo[2]; z <= hi[2] && !near_triangle_[t]; ++z)
            for (std::int64_t y = lo[1]; y <= hi[1] && !near_triangle_[t]; ++y)
                for (std::int64_t x = lo[0]; x <= hi[0] && !near_triangle_[t]; ++x)
                    if (grid_.contains(cube_key(x, y, z, -1))) near_triangle_[t] = true;
    }
}

}  // namespace peensim
