#include "geometry/spur_gear_mesh.h"

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "common/input_error.h"
#include "geometry/axis_frame.h"
#include "geometry/mesh_builder.h"
#include "geometry/polar_surfaces.h"

namespace peensim {

namespace {

using Vec2 = Eigen::Vector2d;

void check(const SpurGearResolution& r, const InvoluteToothProfile& profile) {
    const bool has_radial_flank = profile.root_radius_m() < profile.base_radius_m();
    if ((has_radial_flank && r.radial_flank_segments < 1) || r.radial_flank_segments < 0 || r.involute_segments < 1 ||
        r.tooth_width_segments < 1 || r.root_arc_segments < 1 || r.body_rings < 1 || r.axial_layers < 1) {
        throw InputError({}, "gear", "resolution needs at least one segment per part of the outline");
    }
}

// One circle of the flank sampling: a tooth spans [phi - half_angle, phi + half_angle] on it.
struct FlankRow {
    double radius_m;
    double half_angle_rad;
};

// Rows from the root circle (row 0) up to the tip circle (last row).
std::vector<FlankRow> flank_rows(const InvoluteToothProfile& profile, const SpurGearResolution& r) {
    std::vector<FlankRow> rows;
    const double root = profile.root_radius_m();
    const double start = profile.involute_start_radius_m();
    const int radial = root < profile.base_radius_m() ? r.radial_flank_segments : 0;
    for (int i = 0; i < radial; ++i) {
        const double radius = subdivision(root, start, i, radial);
        rows.push_back({radius, profile.half_angle_rad(radius)});
    }
    // Equal arc lengths along the involute (arc length from the base circle is r_b t^2 / 2, so
    // t^2 is spaced evenly): even edges on the flank walls, no slivers near the base circle.
    const double t_start = profile.roll_angle_at(start);
    const double t_tip = profile.roll_angle_at(profile.tip_radius_m());
    for (int i = 0; i <= r.involute_segments; ++i) {
        const double t_squared = subdivision(t_start * t_start, t_tip * t_tip, i, r.involute_segments);
        double radius = profile.radius_at_roll(std::sqrt(t_squared));
        if (i == 0) radius = start;
        if (i == r.involute_segments) radius = profile.tip_radius_m();
        rows.push_back({radius, profile.half_angle_rad(radius)});
    }
    return rows;
}

// The gear's outline and end face in its plane, as indexed 2-D points.
struct PlanarGear {
    std::vector<Vec2> points;              // m
    std::vector<std::array<int, 3>> face;  // end-face triangles, counter-clockwise
    std::vector<int> outer_loop;           // counter-clockwise around the gear
    std::vector<int> bore_loop;            // clockwise (the bore wall faces the axis)
};

PlanarGear plan_gear(const InvoluteToothProfile& profile, const SpurGearResolution& r, double bore_radius_m) {
    const std::vector<FlankRow> rows = flank_rows(profile, r);
    const int z = profile.teeth();
    const int c = r.tooth_width_segments;
    const int s = r.root_arc_segments;
    const int per_tooth = c + s;  // points per tooth on the root circle
    const int root_points = z * per_tooth;
    const int top_row = static_cast<int>(rows.size()) - 1;
    const double pitch = profile.pitch_angle_rad();
    const double root_half_angle = rows.front().half_angle_rad;

    PlanarGear g;
    auto add_point = [&](double radius, double angle) {
        g.points.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
        return static_cast<int>(g.points.size() - 1);
    };
    auto quad = [&](int a, int b, int cc, int d) {  // counter-clockwise a-b-c-d
        g.face.push_back({a, b, cc});
        g.face.push_back({a, cc, d});
    };

    // Angles on the root circle: c + s per tooth, starting at the tooth's left foot.
    std::vector<double> root_angle(static_cast<std::size_t>(root_points));
    for (int k = 0; k < z; ++k) {
        const double centre = pitch * k;
        for (int j = 0; j < c; ++j)
            root_angle[static_cast<std::size_t>(k * per_tooth + j)] = centre + root_half_angle * (2.0 * j / c - 1.0);
        for (int m = 0; m < s; ++m) {
            root_angle[static_cast<std::size_t>(k * per_tooth + c + m)] =
                centre + root_half_angle + (pitch - 2.0 * root_half_angle) * m / s;
        }
    }
    // Body: rings from the bore (q = 0) to the root circle (q = body_rings).
    std::vector<std::vector<int>> ring(static_cast<std::size_t>(r.body_rings + 1));
    for (int q = 0; q <= r.body_rings; ++q) {
        const double radius = subdivision(bore_radius_m, profile.root_radius_m(), q, r.body_rings);
        for (double angle : root_angle) ring[static_cast<std::size_t>(q)].push_back(add_point(radius, angle));
    }
    auto ring_at = [&](int q, int n) { return ring[static_cast<std::size_t>(q)][static_cast<std::size_t>(n % root_points)]; };
    for (int q = 0; q < r.body_rings; ++q) {
        for (int n = 0; n < root_points; ++n) quad(ring_at(q, n), ring_at(q + 1, n), ring_at(q + 1, n + 1), ring_at(q, n + 1));
    }

    // Teeth: grid (row i, column j); row 0 is the tooth's stretch of the root circle.
    const int root_ring = r.body_rings;
    for (int k = 0; k < z; ++k) {
        std::vector<std::vector<int>> grid(rows.size());
        for (int j = 0; j <= c; ++j) grid[0].push_back(ring_at(root_ring, k * per_tooth + j));
        for (int i = 1; i <= top_row; ++i) {
            const FlankRow& row = rows[static_cast<std::size_t>(i)];
            for (int j = 0; j <= c; ++j)
                grid[static_cast<std::size_t>(i)].push_back(add_point(row.radius_m, pitch * k + row.half_angle_rad * (2.0 * j / c - 1.0)));
        }
        auto at = [&](int i, int j) { return grid[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]; };
        for (int i = 0; i < top_row; ++i) {
            for (int j = 0; j < c; ++j) quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
        }
        // Outline of this tooth and the root arc after it, counter-clockwise.
        for (int i = 0; i <= top_row; ++i) g.outer_loop.push_back(at(i, 0));
        for (int j = 1; j <= c; ++j) g.outer_loop.push_back(at(top_row, j));
        for (int i = top_row - 1; i >= 0; --i) g.outer_loop.push_back(at(i, c));
        for (int m = 1; m < s; ++m) g.outer_loop.push_back(ring_at(root_ring, k * per_tooth + c + m));
    }
    for (int n = root_points; n > 0; --n) g.bore_loop.push_back(ring_at(0, n));
    return g;
}

}  // namespace

TriangleMesh spur_gear(const SpurGearSpec& spec, const SpurGearResolution& resolution) {
    const InvoluteToothProfile profile(spec);
    check(resolution, profile);
    const PlanarGear plan = plan_gear(profile, resolution, spec.bore_radius_m);

    const AxisFrame frame{spec.axis, spec.center_m};
    const double pitch = profile.pitch_angle_rad();
    const int z = profile.teeth();
    MeshBuilder builder;
    for (int k = 0; k < z; ++k) builder.group("tooth-" + std::to_string(k));  // group index k
    auto sector_of = [&](const Vec2& p) {
        const int k = static_cast<int>(std::floor(std::atan2(p.y(), p.x()) / pitch + 0.5));
        return ((k % z) + z) % z;
    };
    auto at = [&](int point, double w) {
        const Vec2& p = plan.points[static_cast<std::size_t>(point)];
        return frame.to_world(p.x(), p.y(), w);
    };

    const double low = -0.5 * spec.face_width_m;
    const double high = 0.5 * spec.face_width_m;
    for (const auto& t : plan.face) {
        const Vec2 centroid = (plan.points[static_cast<std::size_t>(t[0])] + plan.points[static_cast<std::size_t>(t[1])] +
                               plan.points[static_cast<std::size_t>(t[2])]) /
                              3.0;
        const int group = sector_of(centroid);
        builder.add_triangle(at(t[0], high), at(t[1], high), at(t[2], high), group);  // faces +w
        builder.add_triangle(at(t[0], low), at(t[2], low), at(t[1], low), group);     // faces -w
    }
    // Side walls: a loop running counter-clockwise seen from +w gets outward normals from
    // quads (p, q, q above, p above); the bore loop runs clockwise, so its wall faces the axis.
    for (const std::vector<int>* loop : {&plan.outer_loop, &plan.bore_loop}) {
        const std::size_t n = loop->size();
        for (std::size_t e = 0; e < n; ++e) {
            const int p = (*loop)[e];
            const int q = (*loop)[(e + 1) % n];
            const int group = sector_of(0.5 * (plan.points[static_cast<std::size_t>(p)] + plan.points[static_cast<std::size_t>(q)]));
            for (int l = 0; l < resolution.axial_layers; ++l) {
                const double w0 = subdivision(low, high, l, resolution.axial_layers);
                const double w1 = subdivision(low, high, l + 1, resolution.axial_layers);
                builder.add_quad(at(p, w0), at(q, w0), at(q, w1), at(p, w1), group);
            }
        }
    }
    return builder.take();
}

}  // namespace peensim
