#include "app/run/loss_report.h"

#include <sstream>

namespace peensim {

namespace {

std::string point_mm(const Vec3& p) {
    std::ostringstream o;
    o << "(" << p.x() * 1e3 << ", " << p.y() * 1e3 << ", " << p.z() * 1e3 << ") mm";
    return o.str();
}

std::string name_of(const Model& model, int c) {
    return c >= 0 && static_cast<std::size_t>(c) < model.components.size() ? model.components[static_cast<std::size_t>(c)].name : "?";
}

}  // namespace

std::string describe_loss(const Model& model, const LostShot& l) {
    std::ostringstream o;
    const double D_mm = 2e3 * (l.radius_m > 0.0 ? l.radius_m : model.min_shot_radius_m);
    switch (l.cause) {
        case LossCause::leak:
            o << "warning: shot " << l.shot << " left the assembly at t = " << l.time_s << " s through an opening near "
              << point_mm(l.where_m) << " (" << l.clearance_m * 1e3 << " mm from " << name_of(model, l.component)
              << "): its whole sphere flew from " << point_mm(l.from_m) << " (t = " << l.from_time_s
              << " s) out of the chamber's bounds without touching any surface, so the "
              << "assembly is open there by at least the shot diameter (" << D_mm << " mm): check the meshes and their placement";
            break;
        case LossCause::engine_error:
            o << "error: shot " << l.shot << " was lost at t = " << l.time_s
              << " s by an engine error: after its last event at t = " << l.from_time_s << " s at " << point_mm(l.from_m) << " it crossed "
              << name_of(model, l.component) << " at " << point_mm(l.where_m) << " unseen and left at " << point_mm(l.position_m)
              << " (counted in engine_errors; please report this run)";
            break;
        case LossCause::not_diagnosed:
            o << "warning: shot " << l.shot << " left the chamber at t = " << l.time_s << " s near " << point_mm(l.position_m)
              << " (time stepping: not diagnosed; the event-driven scheme tells a leak from an engine error)";
            break;
    }
    return o.str();
}

}  // namespace peensim
