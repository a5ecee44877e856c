// How both stepping schemes turn an impact into the record the writers read: the contact point
// and the relative velocities in the component's own frame at its pose then. One place, so the
// two schemes' logs cannot drift apart in frame or sign.
#pragma once

#include <cstdint>

#include <vector>

#include "contact/contact_law.h"
#include "engine/impact_record.h"
#include "engine/simulation_state.h"
#include "model/model.h"

namespace peensim {

// time_s: absolute simulated time (s); pose: the component's pose at the impact; point_world: the
// contact point (m, world); v_shot_in: the shot's velocity before (m/s, world); v_surface: the
// surface's velocity there (m/s, world); r: the law's response (v_shot after, speeds).
inline ImpactRecord make_impact_record(double time_s, int shot, int component, int triangle, const Pose& pose, const Vec3& point_world,
                                       const Vec3& v_shot_in, const Vec3& v_surface, const contact::SurfaceContactResponse& r) {
    ImpactRecord rec;
    rec.time_s = time_s;
    rec.shot = static_cast<std::int32_t>(shot);
    rec.component = static_cast<std::int32_t>(component);
    rec.triangle = static_cast<std::int32_t>(triangle);
    rec.point_m = pose.to_component(point_world);
    rec.v_in_m_per_s = pose.rotation.transpose() * (v_shot_in - v_surface);
    rec.v_out_m_per_s = pose.rotation.transpose() * (r.v_shot - v_surface);
    rec.vn_in_m_per_s = r.vn_in;
    rec.vt_in_m_per_s = r.vt_in;
    rec.vn_out_m_per_s = r.vn_out;
    return rec;
}

// An impact on component c: counted, and appended to `impacts` if c's impacts are logged (same
// arguments as make_impact_record).
inline void record_impact(const Model& model, SimulationState& state, std::vector<ImpactRecord>& impacts, double time_s, int shot, int c,
                          int triangle, const Pose& pose, const Vec3& point_world, const Vec3& v_shot_in, const Vec3& v_surface,
                          const contact::SurfaceContactResponse& r) {
    ++state.impacts_per_component[static_cast<std::size_t>(c)];
    if (!model.components[static_cast<std::size_t>(c)].logged) return;
    impacts.push_back(make_impact_record(time_s, shot, c, triangle, pose, point_world, v_shot_in, v_surface, r));
    impacts.back().shot_diameter_m = 2.0 * model.shot_sizes[state.shots.size_class[static_cast<std::size_t>(shot)]].radius_m;
}

}  // namespace peensim
