// One soft-sphere contact of the soft scheme while it lasts (engine/soft/soft_pool.h): between a
// shot and a component, or between two shot. What of it outlives a restart point, in the
// simulation state and its checkpoint: its law's per-contact state (the tangential spring), the
// normal it was last seen along, and what its impact record needs from its start (the record is
// written when it ends).
#pragma once

#include "common/vec.h"
#include "contact/soft_pair.h"

namespace peensim {

struct SoftContact {
    int shot = -1;                          // the shot (shot-shot: the lower index of the two)
    int partner = -1;                       // the other shot; -1 for a contact with a component
    int component = -1;                     // the component touched; -1 between two shot
    contact::SoftContactState law_state{};  // its law's own (contact/soft_pair.h: the tangential spring), zeros at its start
    Vec3 normal = Vec3::UnitZ();            // unit, world: from the component's surface (or `partner`) towards `shot`
    double approach_m_per_s = 0.0;          // m/s, normal approach speed when it began (it set the damping)
    double start_time_s = 0.0;              // s, absolute: when it began
    // Component contacts: where it began and how fast, for its impact record (component frame).
    int mesh_triangle = -1;
    Vec3 start_point_m = Vec3::Zero();           // m, contact point
    Vec3 start_velocity_m_per_s = Vec3::Zero();  // m/s, shot relative to the surface
    double start_tangential_m_per_s = 0.0;       // m/s, tangential speed relative to the surface
};

}  // namespace peensim
