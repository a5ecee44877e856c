#include "analysis/surface_cells.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <unordered_map>

#include "analysis/cube_keys.h"
#include "analysis/row_runs.h"
#include "analysis/surface_kernel.h"
#include "common/flat_key_map.h"
#include "common/float_limits.h"
#include "common/parallel_chunks.h"
#include "geometry/mesh_checks.h"

namespace peensim {

namespace {

// Edge groups by (cell, class, line, band).
struct GroupKey {
    std::uint32_t cell;
    std::int32_t line0, line1;
    std::uint16_t cls;
    std::uint8_t band0, band1;
    bool operator==(const GroupKey&) const = default;
};
struct GroupHash {
    std::size_t operator()(const GroupKey& k) const {
        std::uint64_t h = static_cast<std::uint64_t>(k.cell) << 32 | static_cast<std::uint32_t>(k.line0);
        h = h * 0x9E3779B97F4A7C15ull ^
            (static_cast<std::uint64_t>(static_cast<std::uint32_t>(k.line1)) << 24 | static_cast<std::uint64_t>(k.cls) << 8 | k.band0);
        return std::hash<std::uint64_t>()(h * 0x9E3779B97F4A7C15ull ^ k.band1);
    }
};

using GroupIndex = std::unordered_map<GroupKey, std::size_t, GroupHash>;
// The key of the reach groups' map: in cell order (its high bits), then class and band.
std::uint64_t reach_group_key(std::uint32_t cell, std::uint16_t cls, std::uint64_t band) {
    return (static_cast<std::uint64_t>(cell) << 16 | cls) << 8 | band;
}
using ReachSums = std::map<std::uint64_t, std::pair<double, double>>;  // reach_group_key -> (m2, m3)

std::vector<ReachGroup> reach_groups_of(const ReachSums& sums) {
    std::vector<ReachGroup> groups;
    groups.reserve(sums.size());
    for (const auto& [key, m] : sums)
        groups.push_back({static_cast<std::uint32_t>(key >> 24), static_cast<std::uint16_t>(key >> 8 & 0xFFFF),
                          static_cast<std::uint8_t>(key & 0xFF), m.first, m.second});
    return groups;
}

constexpr std::uint8_t kNearLines = 1, kNearSources = 2;

// The cells of side `side` (m) met by a cube of side reach (m) that lists an edge line (kNearLines)
// or holds a boundary source (kNearSources): only in those are a row's runs cut cube by cube. From
// the cubes of side reach, each marking the cells it meets (widened by a hair against rounding):
// a cell's own walk over the cubes within it cost (side / reach)^3 look-ups, minutes for the
// 15 mm cells of a 0.05 s run.
FlatKeyMap<std::uint8_t> cells_near(const EdgeLines& edges, const ReachBoundary& boundary, double side) {
    FlatKeyMap<std::uint8_t> near;
    const double reach = boundary.reach_m(), inverse_side = 1.0 / side;
    const double hair = 1e-9 * (side + reach);
    const auto mark = [&](std::uint64_t key, std::uint8_t what) {
        Vec3 lo, hi;
        for (int k = 0; k < 3; ++k) {
            const auto c = static_cast<double>(cube_axis(key, k));
            lo[k] = c * reach - hair, hi[k] = (c + 1.0) * reach + hair;
        }
        const auto from = cube_of(lo, inverse_side), to = cube_of(hi, inverse_side);
        for (std::int64_t z = from[2]; z <= to[2]; ++z)
            for (std::int64_t y = from[1]; y <= to[1]; ++y)
                for (std::int64_t x = from[0]; x <= to[0]; ++x) *near.try_emplace(cube_key(x, y, z), 0).first |= what;
    };
    if (!edges.lines.empty()) edges.for_each_cube([&](std::uint64_t key) { mark(key, kNearLines); });
    boundary.for_each_source_cube([&](std::uint64_t key) { mark(key, kNearSources); });
    return near;
}

// Floor division of a cube coordinate by m > 0 (the cube of side m x side holding it).
std::int64_t floor_div(std::int64_t a, std::int64_t m) {
    const std::int64_t q = a / m;
    return q * m > a ? q - 1 : q;
}

}  // namespace

SurfaceCells::SurfaceCells(const CoverageProgress& progress, const TriangleMesh& mesh, const EdgeLines& edges,
                           const ReachBoundary& boundary, double side_m) {
    // The triangles in a fixed number of chunks, binned on every core and merged in chunk order:
    // the same sums on any number of cores.
    constexpr std::size_t kBinningChunks = 32;
    const std::size_t triangles = progress.map().triangle_count();
    std::vector<SurfaceCells> parts(kBinningChunks);
    const FlatKeyMap<std::uint8_t> near_cells = cells_near(edges, boundary, side_m);
    for_each_chunk(kBinningChunks, [&](std::size_t c) {
        const auto [first, end] = chunk_range(triangles, kBinningChunks, c);
        parts[c] = SurfaceCells(progress, mesh, edges, boundary, side_m, near_cells, first, end);
    });
    *this = merged(parts, 1);
}

SurfaceCells::SurfaceCells(const CoverageProgress& progress, const TriangleMesh& mesh, const EdgeLines& edges,
                           const ReachBoundary& boundary, double side_m, const FlatKeyMap<std::uint8_t>& near_cells,
                           std::size_t first_triangle, std::size_t end_triangle)
    : side(side_m) {
    const CoverageMap& map = progress.map();
    const SampleClasses& classes = progress.classes();
    const double inverse_side = 1.0 / side;
    FlatKeyMap<std::uint32_t> cell_of;
    std::vector<std::uint8_t> cell_near;  // per cell: kNearLines | kNearSources
    std::unordered_map<std::uint64_t, double> uncovered_of;
    ReachSums near_boundary_of;
    const double band_width = boundary.reach_m() / kReachBands;
    // One grid of cubes of side reach for the edge lines and the boundary's sources.
    const double inverse_reach = 1.0 / boundary.reach_m();
    if (!edges.lines.empty() && edges.inverse_side() != inverse_reach)
        throw std::invalid_argument("SurfaceCells: the edge lines' grid must be the reach boundary's cubes (the same side)");
    GroupIndex group_of;
    // The groups last added to: a row's samples in turn mostly fall in the same one, so each is
    // searched once a change.
    constexpr std::size_t kNoGroup = ~std::size_t{0};
    std::size_t last_group = kNoGroup;
    GroupKey last_group_key{};
    std::pair<double, double>* last_near_boundary = nullptr;
    std::uint64_t last_near_boundary_key = 0;
    double* last_uncovered = nullptr;
    std::uint64_t last_uncovered_key = 0;
    const auto add_uncovered = [&](std::uint32_t cell, std::uint16_t k, double m2) {
        const std::uint64_t key = static_cast<std::uint64_t>(cell) << 16 | k;
        if (!last_uncovered || key != last_uncovered_key) last_uncovered = &uncovered_of[key], last_uncovered_key = key;
        *last_uncovered += m2;
    };
    const auto add_near_boundary = [&](std::uint32_t cell, std::uint16_t k, double d, double area) {
        const auto band = static_cast<std::uint64_t>(std::min<double>(kReachBands - 1, std::floor(d / band_width)));
        const std::uint64_t key = reach_group_key(cell, k, band);
        if (!last_near_boundary || key != last_near_boundary_key) last_near_boundary = &near_boundary_of[key], last_near_boundary_key = key;
        last_near_boundary->first += area, last_near_boundary->second += area * d;
    };
    const auto add_near_edges = [&](std::uint32_t cell, std::uint16_t k, const std::array<EdgeLines::Near, 2>& lines, int n, double area) {
        const auto band = [&](int m) {
            if (m >= n) return std::uint8_t{0};
            const double width =
                edges.lines[static_cast<std::size_t>(lines[static_cast<std::size_t>(m)].line)].largest_radius_m / kEdgeBands;
            return static_cast<std::uint8_t>(
                std::min<double>(kEdgeBands - 1, std::floor(lines[static_cast<std::size_t>(m)].distance_m / width)));
        };
        const GroupKey key{cell, lines[0].line, n > 1 ? lines[1].line : -1, k, band(0), band(1)};
        if (last_group == kNoGroup || !(key == last_group_key)) {
            const auto [it, added] = group_of.try_emplace(key, edge_groups.size());
            if (added) {
                EdgeGroup g;
                g.cell = cell, g.cls = k, g.line[0] = key.line0, g.line[1] = key.line1;
                g.band[0] = key.band0, g.band[1] = key.band1;
                edge_groups.push_back(g);
            }
            last_group = it->second, last_group_key = key;
        }
        EdgeGroup& g = edge_groups[last_group];
        g.uncovered_m2 += area;
        for (int m = 0; m < n; ++m) {
            g.s_sum_m3[m] += area * lines[static_cast<std::size_t>(m)].s_m;
            g.distance_sum_m3[m] += area * lines[static_cast<std::size_t>(m)].distance_m;
        }
    };
    const auto cell_at = [&](const Vec3& p, int face) {
        const std::array<std::int64_t, 3> c = cube_of(p, inverse_side);
        const auto [it, added] = cell_of.try_emplace(cube_key(c[0], c[1], c[2], face), static_cast<std::uint32_t>(reach_m2.size()));
        if (added) {
            cube.push_back(c);
            facing.push_back(face);
            reach_m2.push_back(0.0);
            point_sum.emplace_back(Vec3::Zero());
            normal_sum.emplace_back(Vec3::Zero());
            const std::uint8_t* near = near_cells.find(cube_key(c[0], c[1], c[2]));
            cell_near.push_back(near == nullptr ? 0 : *near);
        }
        return *it;
    };
    // A row is cut into runs of one cell, then of one class, then (along edge lines with impacts)
    // of one cube of the lines' grid, then (near the reach boundary) of one voxel: a run's area and
    // first moments are added in closed form, and its uncovered samples by a popcount unless a
    // line or the boundary lies within reach, when each uncovered sample is placed by its
    // distance to them.
    map.for_each_sample_row(
        first_triangle, end_triangle,
        [&](std::size_t t, const Vec3& first, const Vec3& step, std::int64_t count, double area, std::int64_t index) {
            if (classes.reachable_samples(t) == 0) return;
            const Vec3 normal = triangle_normal(mesh, t);
            const int face = facing_of(normal);
            const bool near_edges = edges.near(t);
            const bool near_boundary = boundary.near(t);
            const std::uint16_t own = classes.triangle_class(t);
            // Samples [i, i + run) of class k in cell `cell`, whose edge lines within reach are
            // `lines` and whose voxel's boundary source is `source`.
            const auto leaf = [&](std::int64_t i, std::int64_t run, std::uint32_t cell, std::uint16_t k, const EdgeLines::Cube& lines,
                                  std::uint32_t source) {
                if (lines.empty() && source == ReachBoundary::kNoSource) {
                    const std::int64_t open = run - map.covered_samples(index + i, run);
                    if (open > 0) add_uncovered(cell, k, static_cast<double>(open) * area);
                    return;
                }
                for (std::int64_t j = i; j < i + run; ++j) {
                    if (map.covered(index + j)) continue;
                    const Vec3 x = first + static_cast<double>(j) * step;
                    std::array<EdgeLines::Near, 2> near;
                    const int n = edges.nearest(x, lines, near);
                    if (n > 0) {
                        add_near_edges(cell, k, near, n, area);
                        continue;
                    }
                    const double d = boundary.distance(x, source);
                    if (std::isfinite(d))
                        add_near_boundary(cell, k, d, area);
                    else
                        add_uncovered(cell, k, area);
                }
            };
            // Samples [i, i + run) of class k in cell `cell`, cube by cube of side reach (where the
            // edge lines' grid and the boundary's cubes coincide), voxel by voxel in a cube with
            // boundary sources.
            const auto by_cube = [&](std::int64_t i, std::int64_t run, std::uint32_t cell, std::uint16_t k) {
                const bool lines_here = near_edges && (cell_near[cell] & kNearLines) != 0;
                const bool sources_here = near_boundary && (cell_near[cell] & kNearSources) != 0;
                if (!lines_here && !sources_here) return leaf(i, run, cell, k, EdgeLines::Cube{}, ReachBoundary::kNoSource);
                const Vec3 p = first + static_cast<double>(i) * step;
                for_each_cube_run(p, step, run, Vec3::Zero(), inverse_reach, [&](std::int64_t a, std::int64_t part) {
                    const Vec3 q = p + static_cast<double>(a) * step;
                    const EdgeLines::Cube lines = lines_here ? edges.cube_at(q) : EdgeLines::Cube{};
                    if (!sources_here || !boundary.sources_near(q)) return leaf(i + a, part, cell, k, lines, ReachBoundary::kNoSource);
                    for_each_cube_run(q, step, part, Vec3::Zero(), boundary.inverse_side(), [&](std::int64_t b, std::int64_t piece) {
                        leaf(i + a + b, piece, cell, k, lines, boundary.source_near(q + static_cast<double>(b) * step));
                    });
                });
            };
            const auto by_class = [&](std::int64_t i, std::int64_t run, std::uint32_t cell, std::uint16_t k) {
                if (!classes.info(k).reachable) return;
                const Vec3 p = first + static_cast<double>(i) * step;
                const double n = static_cast<double>(run);
                reach_m2[cell] += n * area;
                point_sum[cell] += area * (n * p + 0.5 * n * (n - 1.0) * step);
                normal_sum[cell] += n * area * normal;
                if (classes.info(k).peened()) by_cube(i, run, cell, k);
            };
            for_each_cube_run(first, step, count, Vec3::Zero(), inverse_side, [&](std::int64_t i, std::int64_t run) {
                const Vec3 p = first + static_cast<double>(i) * step;
                const std::uint32_t cell = cell_at(p + 0.5 * static_cast<double>(run - 1) * step, face);
                if (own != SampleClasses::kMixed) return by_class(i, run, cell, own);
                for (std::int64_t j = i; j < i + run;) {  // runs of one class
                    const std::uint16_t k = classes.class_of(t, index + j);
                    std::int64_t end = j + 1;
                    while (end < i + run && classes.class_of(t, index + end) == k) ++end;
                    by_class(j, end - j, cell, k);
                    j = end;
                }
            });
        });
    uncovered.assign(uncovered_of.begin(), uncovered_of.end());
    std::sort(uncovered.begin(), uncovered.end());
    reach_groups = reach_groups_of(near_boundary_of);
}

SurfaceCells SurfaceCells::coarsened(int m) const { return merged(std::span<const SurfaceCells>(this, 1), m); }

SurfaceCells SurfaceCells::merged(std::span<const SurfaceCells> parts, int m) {
    SurfaceCells c;
    c.side = parts.empty() ? 0.0 : parts.front().side * m;
    FlatKeyMap<std::uint32_t> cell_of;
    std::unordered_map<std::uint64_t, double> uncovered_of;
    ReachSums reach_of;
    GroupIndex group_of;
    std::vector<std::uint32_t> coarse;  // per cell of a part: its cell in c
    for (const SurfaceCells& part : parts) {
        // Each cell's coarse one, in the order they first appear.
        coarse.resize(part.cube.size());
        for (std::size_t f = 0; f < part.cube.size(); ++f) {
            const std::array<std::int64_t, 3> q{floor_div(part.cube[f][0], m), floor_div(part.cube[f][1], m),
                                                floor_div(part.cube[f][2], m)};
            const auto [it, added] =
                cell_of.try_emplace(cube_key(q[0], q[1], q[2], part.facing[f]), static_cast<std::uint32_t>(c.cube.size()));
            if (added) {
                c.cube.push_back(q);
                c.facing.push_back(part.facing[f]);
                c.reach_m2.push_back(0.0);
                c.point_sum.emplace_back(Vec3::Zero());
                c.normal_sum.emplace_back(Vec3::Zero());
            }
            const std::uint32_t k = *it;
            coarse[f] = k;
            c.reach_m2[k] += part.reach_m2[f];
            c.point_sum[k] += part.point_sum[f];
            c.normal_sum[k] += part.normal_sum[f];
        }
        for (const auto& [key, m2] : part.uncovered)
            uncovered_of[static_cast<std::uint64_t>(coarse[key >> 16]) << 16 | (key & 0xFFFF)] += m2;
        for (const ReachGroup& g : part.reach_groups) {
            auto& [m2, m3] = reach_of[reach_group_key(coarse[g.cell], g.cls, g.band)];
            m2 += g.uncovered_m2, m3 += g.distance_sum_m3;
        }
        for (const EdgeGroup& g : part.edge_groups) {
            const std::uint32_t cell = coarse[g.cell];
            const auto [it, added] =
                group_of.try_emplace(GroupKey{cell, g.line[0], g.line[1], g.cls, g.band[0], g.band[1]}, c.edge_groups.size());
            if (added) {
                EdgeGroup e = g;
                e.cell = cell;
                c.edge_groups.push_back(e);
                continue;
            }
            EdgeGroup& e = c.edge_groups[it->second];
            e.uncovered_m2 += g.uncovered_m2;
            for (int k = 0; k < 2; ++k) e.s_sum_m3[k] += g.s_sum_m3[k], e.distance_sum_m3[k] += g.distance_sum_m3[k];
        }
    }
    c.uncovered.assign(uncovered_of.begin(), uncovered_of.end());
    std::sort(c.uncovered.begin(), c.uncovered.end());
    c.reach_groups = reach_groups_of(reach_of);
    return c;
}

}  // namespace peensim
