// A shot's motion in the event-driven scheme, as a value: where its centre is and how fast it
// moves at any time (a flight's parabola, a ride on a sonotrode's face, sustained contact between
// two substeps, asleep), and how a new motion starts. The scheme, its sustained-contact
// integrator and its pair predictor all read shot through these.
#pragma once

#include "common/vec.h"
#include "engine/event/shot_record.h"
#include "engine/event/wall_predictor.h"

namespace peensim {

// Exact centre (m, world) and velocity (m/s) of shot `s` at time t (s, the scheme's clock).
Vec3 motion_position(const EventShot& s, const WallPredictor& walls, double t);
Vec3 motion_velocity(const EventShot& s, const WallPredictor& walls, double t);

// Starts `motion` at t from centre p (m) and velocity v (m/s) under gravity g (m/s2); bumps the
// shot's version (pair events predicted against the old motion go stale). support: unit normal of
// the surface a shot in sustained contact rests on (zero: none); box_travel_m: the first search
// window of a flight (m of travel).
void start_motion(EventShot& s, const Vec3& p, const Vec3& v, double t, EventMotion motion, const Vec3& g, double box_travel_m,
                  const Vec3& support = Vec3::Zero());

}  // namespace peensim
