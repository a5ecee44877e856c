// One impact of a shot on a logged component, as the engine buffers it during a step
// and the writers read it after the step (the engine never writes files itself).
#pragma once

#include <cstdint>

#include "common/vec.h"

namespace peensim {

struct ImpactRecord {
    double time_s = 0.0;           // s, exact contact time within the step
    std::int32_t shot = 0;         // shot index
    std::int32_t component = 0;    // index into the model's components
    std::int32_t triangle = 0;     // facet index in the component's mesh file
    Vec3 point_m;                  // m, contact point in the component's own frame
    Vec3 v_in_m_per_s;             // m/s, shot velocity relative to the surface before impact, component frame
    double vn_in_m_per_s = 0.0;    // m/s, normal approach speed (positive)
    double vt_in_m_per_s = 0.0;    // m/s, tangential speed relative to the surface before impact
    Vec3 v_out_m_per_s;            // m/s, relative velocity after impact, component frame
    double vn_out_m_per_s = 0.0;   // m/s, normal rebound speed (positive)
    double duration_s = 0.0;       // s, how long the contact lasted (soft scheme; 0: an instantaneous impact)
    double shot_diameter_m = 0.0;  // m, the shot's diameter (its size's)
};

}  // namespace peensim
