// The edge lines of a part with impacts on them (analysis/coverage_forecast.h, "Edge lines"): an
// impact on an edge of its triangle dents only the strip within its dent radius of that line, so
// the coverage forecast estimates their rate along each line. Each line is a segment of the mesh
// shared by the triangles that have it, with its impacts sorted along it, and a grid that finds
// the lines within dent reach of a point.
// Pure computation: no file I/O.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "analysis/coverage_forecast.h"
#include "analysis/cube_keys.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

class EdgeLines {
public:
    struct Line {
        Vec3 start = Vec3::Zero();         // m
        Vec3 along = Vec3::UnitX();        // unit
        double length_m = 0.0;             // m
        double largest_radius_m = 0.0;     // m, of its impacts' dents
        std::size_t first = 0, count = 0;  // its impacts in `impacts`
    };
    struct Impact {
        double s_m = 0.0;       // m along the line
        double radius_m = 0.0;  // m, the dent's
        std::uint8_t batch = 0;
    };
    std::vector<Line> lines;
    std::vector<Impact> impacts;  // line by line, increasing s
    std::uint64_t count = 0;      // edge impacts

    // all: the component's impacts (those on an edge make the lines); grid_side_m (m): the side of
    // the grid's cubes, at least the largest dent radius of a line (std::invalid_argument if not;
    // the coverage forecast gives the reach boundary's, so that one cube of a row serves both).
    EdgeLines(const TriangleMesh& mesh, std::span<const ForecastImpact> all, double grid_side_m);

    bool near(std::size_t t) const { return !near_triangle_.empty() && near_triangle_[t]; }

    // A line within dent reach of a point: which, how far (m, from the infinite line: the dents
    // of radius rho centred on it that cover the point lie on a chord 2 sqrt(rho^2 - d^2) long
    // whatever side the point is on) and where along it (m, the foot of the perpendicular, which
    // lies off the segment for a point beyond its end).
    struct Near {
        std::int32_t line = -1;
        double distance_m = 0.0, s_m = 0.0;
    };
    // The lines listed in one cube of the grid (side: inverse_side()): those whose dents may reach
    // a point in it. A caller walking a row of samples looks a cube up once for all of its samples.
    struct Cube {
        std::uint32_t first = 0, end = 0;  // its lines in grid_lines_
        bool empty() const { return first == end; }
    };
    Cube cube_at(const Vec3& x) const {
        if (lines.empty()) return {};
        const auto* run = grid_.find(cube_key_of(x, inverse_side_));
        return run == nullptr ? Cube{} : Cube{run->first, run->second};
    }
    double inverse_side() const { return inverse_side_; }  // 1/m
    // f(key) for the key (cube_key) of every cube of the grid that lists a line, in no order.
    template <class F>
    void for_each_cube(F&& f) const {
        grid_.for_each([&](std::uint64_t key, const auto&) { f(key); });
    }

    // The (at most) two nearest lines of `cube` (the one holding x) whose largest dent reaches x;
    // returns how many.
    int nearest(const Vec3& x, const Cube& cube, std::array<Near, 2>& out) const {
        int found = 0;
        for (std::uint32_t i = cube.first; i < cube.end; ++i) {
            const std::int32_t id = grid_lines_[i];
            const Line& l = lines[static_cast<std::size_t>(id)];
            const Vec3 r = x - l.start;
            const double foot = r.dot(l.along);
            const double s = std::clamp(foot, 0.0, l.length_m);
            const double d = (r - s * l.along).norm();  // to the segment
            if (!(d < l.largest_radius_m)) continue;
            const Near n{id, (r - foot * l.along).norm(), foot};
            if (found < 2) {
                out[static_cast<std::size_t>(found++)] = n;
            } else if (d < out[1].distance_m) {
                out[1] = n;
            } else {
                continue;
            }
            if (found == 2 && out[1].distance_m < out[0].distance_m) std::swap(out[0], out[1]);
        }
        return found;
    }

    double reach_m = 0.0;  // m, the largest dent radius of any line

private:
    double inverse_side_ = 0.0;
    CubeRuns grid_;
    std::vector<std::int32_t> grid_lines_;
    std::vector<bool> near_triangle_;
};

}  // namespace peensim
