// The coverage forecast's cells (surface_cells.h): fine cells joined m x m x m hold what binning
// the samples at m times their side holds (the forecast joins h's cells for 2 h), for cells finer
// and far coarser than the edge lines' and the boundary's cubes, and the binning gives the same
// bytes on any number of threads.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "analysis/coverage_progress.h"
#include "analysis/edge_lines.h"
#include "analysis/reach_boundary.h"
#include "analysis/regions.h"
#include "analysis/sample_classes.h"
#include "analysis/surface_cells.h"
#include "common/parallel_chunks.h"
#include "common/random.h"
#include "geometry/box_mesh.h"

namespace peensim {
namespace {

constexpr double kDentRadius = 0.125e-3;  // m
// The largest dent radius as the forecast takes it, from the impacts' dent areas (floats): the side
// of the edge lines' grid and of the reach boundary's cubes.
const double kReach = std::sqrt(static_cast<double>(static_cast<float>(M_PI * kDentRadius * kDentRadius)) / M_PI);

// A 20 mm cube off the grid's origin (no sample sits on a cell boundary by construction), out of
// the shot's reach beyond x = 4 mm (a reach boundary across four faces), with dents on its faces
// and on its edges (edge lines).
struct PeenedCube {
    TriangleMesh cube = box(BoxSpec{Vec3::Constant(0.02), Vec3(0.3137e-3, -0.271e-3, 0.1234e-3), Eigen::Vector3i(4, 4, 4)});
    RegionSet regions{cube, {}};
    std::unique_ptr<CoverageProgress> progress;
    std::vector<ForecastImpact> impacts;

    PeenedCube() {
        const ReachTest reach = [](const Vec3& x, std::size_t, double) { return x.x() < 4e-3; };
        const double dent = 2.0 * kDentRadius;
        auto map = std::make_unique<CoverageMap>(cube, dent / 5.0, dent);
        SampleClasses classes(*map, cube, regions, reach, 1e-3, dent);
        progress = std::make_unique<CoverageProgress>(std::move(map), std::move(classes), 0.98);
        Random rng(3);
        for (int i = 0; i < 4000; ++i) {
            const auto t = static_cast<std::size_t>(rng.uniform() * static_cast<double>(cube.triangle_count()));
            const Vec3 a = cube.corner(t, 0), b = cube.corner(t, 1), c = cube.corner(t, 2);
            ForecastImpact f;
            Vec3 x;
            if (i % 4 == 0) {  // on an edge of its triangle
                const int k = static_cast<int>(rng.uniform() * 3.0);
                x = cube.corner(t, k) + rng.uniform() * (cube.corner(t, (k + 1) % 3) - cube.corner(t, k));
                f.edge = static_cast<std::int8_t>(k);
            } else {
                double u = rng.uniform(), v = rng.uniform();
                if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
                x = a + u * (b - a) + v * (c - a);
            }
            if (!(x.x() < 4e-3)) continue;
            progress->add_dent(x, dent, i * 1e-3);
            for (int k = 0; k < 3; ++k) f.point_m[k] = static_cast<float>(x[k]);
            f.triangle = static_cast<std::uint32_t>(t);
            f.dent_area_m2 = static_cast<float>(M_PI * kDentRadius * kDentRadius);
            f.batch = static_cast<std::uint8_t>(i % 10);
            impacts.push_back(f);
        }
    }
};

// A cell's identity across binnings: its cube and facing.
using CellKey = std::tuple<std::int64_t, std::int64_t, std::int64_t, int>;
CellKey key_of(const SurfaceCells& s, std::uint32_t cell) { return {s.cube[cell][0], s.cube[cell][1], s.cube[cell][2], s.facing[cell]}; }

// Everything the cells hold, keyed by what it belongs to rather than by the cells' numbering.
struct Contents {
    std::map<CellKey, std::array<double, 7>> cells;  // reach m2, point sum, normal sum
    std::map<std::tuple<CellKey, int>, double> uncovered;
    std::map<std::tuple<CellKey, int, int>, std::array<double, 2>> reach_groups;
    std::map<std::tuple<CellKey, int, int, int, int, int>, std::array<double, 5>> edge_groups;
};

Contents contents_of(const SurfaceCells& s) {
    Contents c;
    for (std::uint32_t k = 0; k < s.cube.size(); ++k)
        c.cells[key_of(s, k)] = {s.reach_m2[k],       s.point_sum[k].x(),  s.point_sum[k].y(), s.point_sum[k].z(),
                                 s.normal_sum[k].x(), s.normal_sum[k].y(), s.normal_sum[k].z()};
    for (const auto& [pair, m2] : s.uncovered)
        c.uncovered[{key_of(s, static_cast<std::uint32_t>(pair >> 16)), static_cast<int>(pair & 0xFFFF)}] += m2;
    for (const ReachGroup& g : s.reach_groups) c.reach_groups[{key_of(s, g.cell), g.cls, g.band}] = {g.uncovered_m2, g.distance_sum_m3};
    for (const EdgeGroup& g : s.edge_groups)
        c.edge_groups[{key_of(s, g.cell), g.cls, g.line[0], g.line[1], g.band[0], g.band[1]}] = {
            g.uncovered_m2, g.s_sum_m3[0], g.s_sum_m3[1], g.distance_sum_m3[0], g.distance_sum_m3[1]};
    return c;
}

template <class Map>
void expect_same_sums(const Map& a, const Map& b, double scale, const char* what) {
    ASSERT_EQ(a.size(), b.size()) << what;
    for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j) {
        ASSERT_TRUE(i->first == j->first) << what;
        if constexpr (std::is_same_v<typename Map::mapped_type, double>) {
            EXPECT_NEAR(i->second, j->second, 1e-12 * scale) << what;
        } else {
            for (std::size_t k = 0; k < i->second.size(); ++k) EXPECT_NEAR(i->second[k], j->second[k], 1e-12 * scale) << what << " " << k;
        }
    }
}

TEST(SurfaceCells, FineCellsJoinedHoldWhatBinningAtTheirSideHolds) {
    const PeenedCube p;
    const EdgeLines edges(p.cube, p.impacts, kReach);
    const ReachBoundary boundary(*p.progress, p.cube, kReach);
    ASSERT_GT(edges.lines.size(), 10u);
    const double fine = 0.3e-3;  // m
    const Contents joined = contents_of(SurfaceCells(*p.progress, p.cube, edges, boundary, fine).coarsened(4));
    const Contents direct = contents_of(SurfaceCells(*p.progress, p.cube, edges, boundary, 4.0 * fine));
    // The scene holds all kinds: cells out of reach and within it, uncovered samples away from
    // lines and the boundary, near the boundary, near lines.
    EXPECT_GT(direct.cells.size(), 100u);
    EXPECT_GT(direct.uncovered.size(), 100u);
    EXPECT_GT(direct.reach_groups.size(), 10u);
    EXPECT_GT(direct.edge_groups.size(), 100u);
    const double area = 6 * 0.02 * 0.02;  // m2, the scale of every area sum (and x 0.01 m of the moments: looser)
    expect_same_sums(joined.cells, direct.cells, area, "cells");
    expect_same_sums(joined.uncovered, direct.uncovered, area, "uncovered");
    expect_same_sums(joined.reach_groups, direct.reach_groups, area, "reach groups");
    expect_same_sums(joined.edge_groups, direct.edge_groups, area, "edge groups");
}

// Cells smaller than the cubes of side reach that list the edge lines and the boundary's sources,
// and cells 40 times larger (a short run's forecast: few impacts, a kernel centimetres wide): each
// cell that such a cube meets is cut cube by cube, wherever the cubes fall in it.
TEST(SurfaceCells, CellsFinerOrFarCoarserThanTheReachHoldTheSame) {
    const PeenedCube p;
    const EdgeLines edges(p.cube, p.impacts, kReach);
    const ReachBoundary boundary(*p.progress, p.cube, kReach);
    const double fine = 0.1e-3;  // m, below kReach
    ASSERT_LT(fine, kReach);
    const Contents joined = contents_of(SurfaceCells(*p.progress, p.cube, edges, boundary, fine).coarsened(50));
    const Contents direct = contents_of(SurfaceCells(*p.progress, p.cube, edges, boundary, 50.0 * fine));
    EXPECT_GT(direct.reach_groups.size(), 10u);
    EXPECT_GT(direct.edge_groups.size(), 100u);
    const double area = 6 * 0.02 * 0.02;  // m2
    expect_same_sums(joined.cells, direct.cells, area, "cells");
    expect_same_sums(joined.uncovered, direct.uncovered, area, "uncovered");
    expect_same_sums(joined.reach_groups, direct.reach_groups, area, "reach groups");
    expect_same_sums(joined.edge_groups, direct.edge_groups, area, "edge groups");
}

TEST(SurfaceCells, TheEdgeLinesAndTheBoundaryMustShareTheirGrid) {
    const PeenedCube p;
    EXPECT_THROW(EdgeLines(p.cube, p.impacts, 0.5 * kReach), std::invalid_argument);
    const EdgeLines edges(p.cube, p.impacts, 2.0 * kReach);
    const ReachBoundary boundary(*p.progress, p.cube, kReach);
    EXPECT_THROW(SurfaceCells(*p.progress, p.cube, edges, boundary, 1e-3), std::invalid_argument);
}

TEST(SurfaceCells, TheSameBytesOnAnyNumberOfThreads) {
    const PeenedCube p;
    const EdgeLines edges(p.cube, p.impacts, kReach);
    const ReachBoundary boundary(*p.progress, p.cube, kReach);
    set_analysis_threads(1);
    const SurfaceCells one(*p.progress, p.cube, edges, boundary, 0.4e-3);
    set_analysis_threads(5);
    const SurfaceCells five(*p.progress, p.cube, edges, boundary, 0.4e-3);
    set_analysis_threads(0);
    EXPECT_EQ(one.cube, five.cube);
    EXPECT_EQ(one.facing, five.facing);
    EXPECT_EQ(one.reach_m2, five.reach_m2);
    EXPECT_EQ(one.point_sum, five.point_sum);
    EXPECT_EQ(one.normal_sum, five.normal_sum);
    EXPECT_EQ(one.uncovered, five.uncovered);
    ASSERT_EQ(one.reach_groups.size(), five.reach_groups.size());
    for (std::size_t g = 0; g < one.reach_groups.size(); ++g) {
        EXPECT_EQ(one.reach_groups[g].cell, five.reach_groups[g].cell);
        EXPECT_EQ(one.reach_groups[g].distance_sum_m3, five.reach_groups[g].distance_sum_m3);
    }
    ASSERT_EQ(one.edge_groups.size(), five.edge_groups.size());
    for (std::size_t g = 0; g < one.edge_groups.size(); ++g) {
        EXPECT_EQ(one.edge_groups[g].cell, five.edge_groups[g].cell);
        EXPECT_EQ(one.edge_groups[g].uncovered_m2, five.edge_groups[g].uncovered_m2);
        EXPECT_EQ(one.edge_groups[g].s_sum_m3[0], five.edge_groups[g].s_sum_m3[0]);
    }
}

}  // namespace
}  // namespace peensim
