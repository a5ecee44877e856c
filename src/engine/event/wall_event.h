// A shot's next event with a surface in the event-driven scheme: a contact, or one of the
// self-scheduled events of its motion (a window end, a launch from a ride, a substep of sustained
// contact, leaving the world box). Times are on the scheme's clock (seconds since its epoch).
#pragma once

#include "common/vec.h"

namespace peensim {

// Fraction of R: a gap this small is a touch (conservative advancement stops there; a graze is
// searched again from this far on; a shot-shot overlap shallower than this is left alone).
inline constexpr double kTouchDistance = 1e-9;
// Fraction of R: a shot this close to a surface or a shot touches it (sustained contact, sleep).
inline constexpr double kContactSlack = 1e-6;

// sink: the centre enters one of the model's sinks (`component` is the sink's index there).
enum class WallKind : unsigned char { none, contact, launch, substep, leave, sink };

// The next contact of a shot with a component, world frame, at `time`.
struct WallEvent {
    double time = 0.0;  // s
    WallKind kind = WallKind::none;
    int component = -1;
    int triangle = -1;                         // facet of the mesh file (impact record)
    int mesh_triangle = -1;                    // triangle of the component's mesh (static and moving meshes)
    bool overlapping = false;                  // found inside the surface at the prediction's start
    bool face = false;                         // on the sonotrode's vibrating face
    Vec3 point = Vec3::Zero();                 // m, surface point
    Vec3 normal = Vec3::UnitZ();               // unit, from the surface towards the centre
    Vec3 surface_velocity = Vec3::Zero();      // m/s
    Vec3 surface_acceleration = Vec3::Zero();  // m/s2
    double depth = 0.0;                        // m, overlap depth if overlapping
    // kind none: the search of `component` ran out of iterations and resumes from `time` (nothing
    // found before it); see EventStepping's search fallback.
    bool resumed = false;
};

}  // namespace peensim
