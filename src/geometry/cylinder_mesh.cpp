#include "geometry/cylinder_mesh.h"

#include "common/input_error.h"
#include "geometry/mesh_builder.h"
#include "geometry/polar_surfaces.h"

namespace peensim {

TriangleMesh cylinder(const CylinderSpec& spec) {
    if (!(spec.radius_m > 0.0) || !(spec.height_m > 0.0)) {
        throw InputError({}, "cylinder", "radius and height must be positive");
    }
    if (spec.segments < 3 || spec.axial_subdivisions < 1 || spec.cap_rings < 1) {
        throw InputError({}, "cylinder", "needs at least 3 segments, 1 axial subdivision and 1 cap ring");
    }
    const AxisFrame frame{spec.axis, spec.center_m};
    const CircleSampling circle(spec.segments);
    const double low = -0.5 * spec.height_m;
    const double high = 0.5 * spec.height_m;

    MeshBuilder builder;
    add_tube_wall(builder, frame, circle, spec.radius_m, low, high, spec.axial_subdivisions, true, builder.group("wall"));
    if (spec.capped) {
        add_flat_ring(builder, frame, circle, 0.0, spec.radius_m, spec.cap_rings, low, false, builder.group("cap-low"));
        add_flat_ring(builder, frame, circle, 0.0, spec.radius_m, spec.cap_rings, high, true, builder.group("cap-high"));
    }
    return builder.take();
}

}  // namespace peensim
