#include "geometry/blade_mesh.h"

#include <cmath>
#include <vector>

#include "common/input_error.h"
#include "geometry/mesh_builder.h"

namespace peensim {

TriangleMesh blade(const BladeSpec& spec) {
    if (!(spec.chord_m > 0.0) || !(spec.span_m > 0.0) || !(spec.thickness_m > 0.0))
        throw InputError({}, "blade", "chord, span and thickness must be positive");
    if (!(spec.thickness_m < spec.chord_m)) throw InputError({}, "blade", "the thickness must be less than the chord");
    if (spec.span_stations < 2 || spec.chord_points < 2) throw InputError({}, "blade", "needs at least 2 span stations and 2 chord points");
    if (!std::isfinite(spec.twist_rad)) throw InputError({}, "blade", "the twist must be finite");
    const AxisFrame frame{spec.axis, spec.center_m};
    const int n = spec.chord_points;
    // One section, untwisted, as a closed loop (u along the chord, v across it): the upper side from
    // edge to edge, then the lower side back, the two edge points shared.
    std::vector<std::pair<double, double>> loop;
    for (int i = 0; i <= n; ++i) {
        const double s = 0.5 * (1.0 - std::cos(M_PI * i / n));  // cosine spacing: finest at the edges
        loop.emplace_back((s - 0.5) * spec.chord_m, 0.5 * spec.thickness_m * 4.0 * s * (1.0 - s));
    }
    for (int i = n - 1; i >= 1; --i) loop.emplace_back(loop[static_cast<std::size_t>(i)].first, -loop[static_cast<std::size_t>(i)].second);
    const auto m = static_cast<int>(loop.size());  // 2 n
    // The point of the loop k at station j (m, world).
    const auto at = [&](int j, int k) {
        const double f = static_cast<double>(j) / (spec.span_stations - 1);
        const double angle = (f - 0.5) * spec.twist_rad;
        const double c = std::cos(angle), s = std::sin(angle);
        const auto [u, v] = loop[static_cast<std::size_t>(k % m)];
        return frame.to_world(c * u - s * v, s * u + c * v, (f - 0.5) * spec.span_m);
    };
    MeshBuilder builder;
    const int surface = builder.group("surface");
    // The loop runs clockwise seen from +w (+u along v > 0, back along v < 0), so a quad from
    // station j to j + 1 and on along the loop has the normal w x (loop direction): outward.
    for (int j = 0; j + 1 < spec.span_stations; ++j)
        for (int k = 0; k < m; ++k) builder.add_quad(at(j, k), at(j + 1, k), at(j + 1, k + 1), at(j, k + 1), surface);
    // The caps: strips across the lens between the upper point i and the lower point (its mirror);
    // at the edges a strip closes to a triangle.
    const auto cap = [&](int j, bool high, int group) {
        for (int i = 0; i < n; ++i) {
            const int up0 = i, up1 = i + 1;
            const int lo0 = i == 0 ? 0 : m - i, lo1 = i + 1 == n ? n : m - i - 1;
            const Vec3 a = at(j, up0), b = at(j, up1), c = at(j, lo1), d = at(j, lo0);
            if (i == 0) {
                high ? builder.add_triangle(a, c, b, group) : builder.add_triangle(a, b, c, group);
            } else if (i + 1 == n) {
                high ? builder.add_triangle(a, d, b, group) : builder.add_triangle(a, b, d, group);
            } else {
                high ? builder.add_quad(a, d, c, b, group) : builder.add_quad(a, b, c, d, group);
            }
        }
    };
    cap(0, false, builder.group("end-low"));
    cap(spec.span_stations - 1, true, builder.group("end-high"));
    return builder.take();
}

}  // namespace peensim
