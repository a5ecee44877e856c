#include "engine/event/shot_motion.h"

namespace peensim {

Vec3 motion_position(const EventShot& s, const WallPredictor& walls, double t) {
    if (s.motion == EventMotion::riding) {
        const VibratingPlane& plane = walls.face(static_cast<std::size_t>(s.ride_component)).plane;
        return s.ride_point + plane.axis * (plane.displacement(t) - plane.displacement(s.ride_start)) +
               s.ride_tangential * (t - s.ride_start);
    }
    return s.path.position(t);
}

Vec3 motion_velocity(const EventShot& s, const WallPredictor& walls, double t) {
    if (s.motion == EventMotion::riding)
        return walls.face(static_cast<std::size_t>(s.ride_component)).plane.velocity(t) + s.ride_tangential;
    return s.path.velocity(t);
}

void start_motion(EventShot& s, const Vec3& p, const Vec3& v, double t, EventMotion motion, const Vec3& g_world, double box_travel_m,
                  const Vec3& support) {
    const bool still = motion == EventMotion::sleeping || motion == EventMotion::riding;
    Vec3 g = still ? Vec3(Vec3::Zero()) : g_world;
    // A shot in sustained contact slides along its support: the support takes gravity's pressing
    // part, so that the shot neither sinks into it between substeps nor leaves it.
    if (motion == EventMotion::sustained && g.dot(support) < 0.0) g -= g.dot(support) * support;
    s.path = Trajectory{p, motion == EventMotion::sleeping ? Vec3(Vec3::Zero()) : v, g, t};
    if (motion != EventMotion::sustained && motion != EventMotion::sleeping) s.quiet_substeps = 0;
    s.window_travel = box_travel_m;
    s.motion = motion;
    ++s.version;
}

}  // namespace peensim
