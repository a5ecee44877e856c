// Building blocks of round shapes (cylinders, the stepped chamber): tube walls and flat
// disks/annuli around a local w axis, sampled at the same angles so that pieces built from
// the same CircleSampling, radius and height share their rim vertices exactly (the builder
// welds them) and the assembled surface is watertight.
#pragma once

#include <vector>

#include "geometry/axis_frame.h"
#include "geometry/mesh_builder.h"

namespace peensim {

// cos and sin of 2 pi j / segments, j = 0 .. segments - 1, computed once so that every ring
// of a shape uses bit-identical directions.
class CircleSampling {
public:
    explicit CircleSampling(int segments);
    int segments() const { return static_cast<int>(cos_.size()); }
    // Point at angle index j (taken modulo segments) on the circle of radius_m at height w_m.
    Vec3 point(const AxisFrame& frame, double radius_m, int j, double w_m) const;

private:
    std::vector<double> cos_;
    std::vector<double> sin_;
};

// Value k / count of the way from `from` to `to`; exactly `to` at k = count (no rounding drift),
// so that separately built pieces meet at identical coordinates.
double subdivision(double from, double to, int k, int count);

// Tube wall of radius_m from w0_m to w1_m in `layers` rings of quads. facing_away_from_axis:
// normals point away from the axis (outside of a solid rod), else towards it (inside of a tube).
void add_tube_wall(MeshBuilder& builder, const AxisFrame& frame, const CircleSampling& circle, double radius_m, double w0_m, double w1_m,
                   int layers, bool facing_away_from_axis, int group);

// Flat annulus at height w_m from inner_radius_m (0 = a full disk, its centre a fan) to
// outer_radius_m in `rings` rings. facing_plus_w: normals along +w, else along -w.
void add_flat_ring(MeshBuilder& builder, const AxisFrame& frame, const CircleSampling& circle, double inner_radius_m, double outer_radius_m,
                   int rings, double w_m, bool facing_plus_w, int group);

}  // namespace peensim
