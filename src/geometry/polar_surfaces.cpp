#include "geometry/polar_surfaces.h"

#include <cmath>
#include <numbers>

namespace peensim {

CircleSampling::CircleSampling(int segments) {
    cos_.reserve(static_cast<std::size_t>(segments));
    sin_.reserve(static_cast<std::size_t>(segments));
    for (int j = 0; j < segments; ++j) {
        const double angle = 2.0 * std::numbers::pi * j / segments;
        cos_.push_back(std::cos(angle));
        sin_.push_back(std::sin(angle));
    }
}

Vec3 CircleSampling::point(const AxisFrame& frame, double radius_m, int j, double w_m) const {
    const auto index = static_cast<std::size_t>(j % segments());
    return frame.to_world(radius_m * cos_[index], radius_m * sin_[index], w_m);
}

double subdivision(double from, double to, int k, int count) {
    if (k == count) return to;
    if (k == 0) return from;
    return from + (to - from) * k / count;
}

void add_tube_wall(MeshBuilder& builder, const AxisFrame& frame, const CircleSampling& circle, double radius_m, double w0_m, double w1_m,
                   int layers, bool facing_away_from_axis, int group) {
    for (int l = 0; l < layers; ++l) {
        const double lo = subdivision(w0_m, w1_m, l, layers);
        const double hi = subdivision(w0_m, w1_m, l + 1, layers);
        for (int j = 0; j < circle.segments(); ++j) {
            const Vec3 a = circle.point(frame, radius_m, j, lo);
            const Vec3 b = circle.point(frame, radius_m, j + 1, lo);
            const Vec3 c = circle.point(frame, radius_m, j + 1, hi);
            const Vec3 d = circle.point(frame, radius_m, j, hi);
            // a -> b runs with increasing angle (counter-clockwise around +w), then up: the
            // normal (b - a) x (d - a) points away from the axis when w1 > w0.
            if (facing_away_from_axis == (w1_m > w0_m)) {
                builder.add_quad(a, b, c, d, group);
            } else {
                builder.add_quad(a, d, c, b, group);
            }
        }
    }
}

void add_flat_ring(MeshBuilder& builder, const AxisFrame& frame, const CircleSampling& circle, double inner_radius_m, double outer_radius_m,
                   int rings, double w_m, bool facing_plus_w, int group) {
    for (int q = 0; q < rings; ++q) {
        const double r_in = subdivision(inner_radius_m, outer_radius_m, q, rings);
        const double r_out = subdivision(inner_radius_m, outer_radius_m, q + 1, rings);
        for (int j = 0; j < circle.segments(); ++j) {
            // Counter-clockwise seen from +w: outward along j, then round, then back in.
            const Vec3 a = circle.point(frame, r_out, j, w_m);
            const Vec3 b = circle.point(frame, r_out, j + 1, w_m);
            if (r_in == 0.0) {
                const Vec3 centre = frame.to_world(0.0, 0.0, w_m);
                if (facing_plus_w)
                    builder.add_triangle(centre, a, b, group);
                else
                    builder.add_triangle(centre, b, a, group);
                continue;
            }
            const Vec3 c = circle.point(frame, r_in, j + 1, w_m);
            const Vec3 d = circle.point(frame, r_in, j, w_m);
            if (facing_plus_w)
                builder.add_quad(d, a, b, c, group);
            else
                builder.add_quad(d, c, b, a, group);
        }
    }
}

}  // namespace peensim
