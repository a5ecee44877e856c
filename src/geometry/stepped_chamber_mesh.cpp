#include "geometry/stepped_chamber_mesh.h"

#include "common/input_error.h"
#include "geometry/axis_frame.h"
#include "geometry/mesh_builder.h"
#include "geometry/polar_surfaces.h"

namespace peensim {

TriangleMesh stepped_tube_chamber(const SteppedChamberSpec& spec) {
    if (!(spec.lower_radius_m > 0.0 && spec.upper_radius_m > spec.lower_radius_m)) {
        throw InputError({}, "chamber", "radii must satisfy 0 < lower radius < upper radius");
    }
    if (!(spec.bottom_z_m < spec.step_z_m && spec.step_z_m < spec.lid_z_m)) {
        throw InputError({}, "chamber", "heights must satisfy bottom z < step z < lid z");
    }
    if (spec.segments < 3 || spec.lower_layers < 1 || spec.upper_layers < 1 || spec.step_rings < 1 || spec.lid_rings < 1) {
        throw InputError({}, "chamber", "needs at least 3 segments and 1 layer or ring per part");
    }
    const AxisFrame frame{Axis::z, Vec3::Zero()};
    const CircleSampling circle(spec.segments);
    const bool facing_away_from_axis = false;  // the cavity is on the axis side of the walls
    const bool facing_up = true;

    MeshBuilder builder;
    add_tube_wall(builder, frame, circle, spec.lower_radius_m, spec.bottom_z_m, spec.step_z_m, spec.lower_layers, facing_away_from_axis,
                  builder.group("lower-wall"));
    add_flat_ring(builder, frame, circle, spec.lower_radius_m, spec.upper_radius_m, spec.step_rings, spec.step_z_m, facing_up,
                  builder.group("step"));
    add_tube_wall(builder, frame, circle, spec.upper_radius_m, spec.step_z_m, spec.lid_z_m, spec.upper_layers, facing_away_from_axis,
                  builder.group("upper-wall"));
    add_flat_ring(builder, frame, circle, 0.0, spec.upper_radius_m, spec.lid_rings, spec.lid_z_m, !facing_up, builder.group("lid"));
    return builder.take();
}

}  // namespace peensim
