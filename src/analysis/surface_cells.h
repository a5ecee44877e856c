// The coverage forecast's cells (analysis/coverage_forecast.h): a part's coverage samples binned
// into cells of (cube of side `side`, facing), each with its reachable area and that area's first
// moments, and the uncovered peened area of each class in it; the uncovered samples near an edge
// line with impacts, and those near the reach boundary, grouped apart by their distance to it.
//
// Why coarsened. Binning walks every coverage sample (51 million on the shipped gear), and near
// edge lines and the reach boundary each one is placed by its distance: a quarter of a second a
// binning. The forecast asks for cells of side h / 4 for each kernel radius h it tries, and for
// 2 h: coarsened(2) joins 2 x 2 x 2 cells of h's (the cubes nest exactly), which costs a pass over
// the cells only. Every sum is the same as binning the samples directly at side 2 x side, up to
// the order of the additions.
// Pure computation: no file I/O.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "analysis/coverage_progress.h"
#include "analysis/edge_lines.h"
#include "analysis/reach_boundary.h"
#include "common/flat_key_map.h"
#include "common/vec.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

// The uncovered samples of one cell and class near the same one or two edge lines, each in the
// same band of distance to it (kEdgeBands per largest dent radius of the line).
struct EdgeGroup {
    std::uint32_t cell = 0;
    std::uint16_t cls = 0;
    std::int32_t line[2] = {-1, -1};
    std::uint8_t band[2] = {0, 0};
    double uncovered_m2 = 0.0;               // m2
    double s_sum_m3[2] = {0.0, 0.0};         // m3: sum of area x position along each line
    double distance_sum_m3[2] = {0.0, 0.0};  // m3: sum of area x distance to it
};

// The uncovered samples of one cell and class within a dent radius of the reach boundary, in the
// same band of distance to it (kReachBands per largest dent radius).
struct ReachGroup {
    std::uint32_t cell = 0;
    std::uint16_t cls = 0;
    std::uint8_t band = 0;
    double uncovered_m2 = 0.0;     // m2
    double distance_sum_m3 = 0.0;  // m3: sum of area x distance to the boundary
};

struct SurfaceCells {
    double side = 0.0;  // m
    std::vector<std::array<std::int64_t, 3>> cube;
    std::vector<int> facing;
    std::vector<double> reach_m2;                             // m2
    std::vector<Vec3> point_sum;                              // m3: sum of area x position
    std::vector<Vec3> normal_sum;                             // m2: sum of area x unit normal
    std::vector<std::pair<std::uint64_t, double>> uncovered;  // (cell << 16 | class, m2), sorted, away from edge lines and the boundary
    std::vector<EdgeGroup> edge_groups;                       // the uncovered samples near edge lines
    std::vector<ReachGroup> reach_groups;                     // the uncovered samples near the reach boundary, in cell order

    // The samples of the progress's map binned into cubes of side side_m (m). The edge lines'
    // grid and the reach boundary's cubes must have the same side (std::invalid_argument if not).
    SurfaceCells(const CoverageProgress& progress, const TriangleMesh& mesh, const EdgeLines& edges, const ReachBoundary& boundary,
                 double side_m);

    // The same surface in cells of m x m x m of these (m >= 1): cubes of side m x side.
    SurfaceCells coarsened(int m) const;

    // Cells of m x m x m of those of `parts` (all of one side; m >= 1), in the order they first
    // appear part by part: the parts of a surface binned apart, joined.
    static SurfaceCells merged(std::span<const SurfaceCells> parts, int m);

    SurfaceCells() = default;  // no cells

private:
    // The samples of the triangles [first_triangle, end_triangle) only.
    // near_cells: per cube of side side_m (cube_key, no facing), whether a cube of side reach that
    // meets it lists an edge line (1) or holds a boundary source (2).
    SurfaceCells(const CoverageProgress& progress, const TriangleMesh& mesh, const EdgeLines& edges, const ReachBoundary& boundary,
                 double side_m, const FlatKeyMap<std::uint8_t>& near_cells, std::size_t first_triangle, std::size_t end_triangle);
};

}  // namespace peensim
