#include "geometry/part_envelope.h"

#include <algorithm>
#include <cmath>

namespace peensim {

namespace {

Vec3 unit_vector(Axis a) {
    switch (a) {
        case Axis::x: return Vec3::UnitX();
        case Axis::y: return Vec3::UnitY();
        case Axis::z: break;
    }
    return Vec3::UnitZ();
}

}  // namespace

PartEnvelope part_envelope(const TriangleMesh& mesh, std::optional<Axis> turning_axis) {
    PartEnvelope e;
    if (mesh.vertices.empty()) return e;
    Vec3 lo = mesh.vertices.front(), hi = lo;
    for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    e.centre_m = 0.5 * (lo + hi);
    e.size_m = hi - lo;
    e.lo_m = lo;
    e.hi_m = hi;
    if (!turning_axis) {
        for (const Vec3& v : mesh.vertices)
            e.footprint_radius_m = std::max(e.footprint_radius_m, std::hypot(v.x() - e.centre_m.x(), v.y() - e.centre_m.y()));
        return e;
    }
    // Each vertex sweeps a circle of radius rho about the axis, at axial offset t from the centre:
    // it reaches rho either way along both other world axes, and (about a level axis) the
    // vertical line at sqrt(t^2 + rho^2) where the circle lies level.
    const Vec3 axis = unit_vector(*turning_axis);
    const bool upright = *turning_axis == Axis::z;
    double t_lo = 0.0, t_hi = 0.0;
    for (const Vec3& v : mesh.vertices) {
        const Vec3 w = v - e.centre_m;
        const double t = w.dot(axis);
        const double rho = (w - t * axis).norm();
        e.swept_radius_m = std::max(e.swept_radius_m, rho);
        t_lo = std::min(t_lo, t), t_hi = std::max(t_hi, t);
        e.footprint_radius_m = std::max(e.footprint_radius_m, upright ? rho : std::hypot(t, rho));
    }
    const Vec3 across = Vec3::Ones() - axis;  // the two world axes the circles turn in
    e.lo_m = e.centre_m + t_lo * axis - e.swept_radius_m * across;
    e.hi_m = e.centre_m + t_hi * axis + e.swept_radius_m * across;
    return e;
}

}  // namespace peensim
