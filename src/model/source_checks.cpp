#include "model/source_checks.h"

#include <cmath>

#include "geometry/mesh_checks.h"
#include "geometry/winding_number.h"
#include "model/shot_cavity.h"

namespace peensim {

namespace {

// A turning part is checked at this many angles over its turn (a 1 deg step moves a point 0.35 mm
// at 20 mm from the axis: finer than any nozzle exit).
constexpr int kTurnAngles = 360;

enum class Inside { no, at_rest, as_it_turns };

// Whether the world point p lies inside component c (closed mesh) at t = 0 or, turning, at any angle.
Inside inside_component(const Component& c, const Vec3& p_w) {
    const Pose rest = c.kinematics.pose(SimTime{});
    const Vec3 p_c = rest.rotation.transpose() * (p_w - rest.translation);
    if (std::abs(winding_number(*c.mesh, p_c)) > 0.5) return Inside::at_rest;
    const Kinematics& k = c.kinematics;
    if (k.kind != Kinematics::Kind::rotating || k.omega_rad_per_s == 0.0) return Inside::no;
    // The part turned by +a holds p where the part at rest holds p turned by -a about the axis.
    for (int i = 1; i < kTurnAngles; ++i) {
        const double a = 2.0 * M_PI * i / kTurnAngles;
        const Vec3 q_w = k.axis_point_m + Eigen::AngleAxisd(-a, k.axis_direction) * (p_w - k.axis_point_m);
        if (std::abs(winding_number(*c.mesh, rest.rotation.transpose() * (q_w - rest.translation))) > 0.5) return Inside::as_it_turns;
    }
    return Inside::no;
}

}  // namespace

std::vector<AssemblyIssue> source_issues(const Model& m) {
    std::vector<AssemblyIssue> out;
    for (std::size_t s = 0; s < m.sources.size() && s < m.description.sources.size(); ++s) {
        const SourceOutline o = m.sources[s]->outline();
        const Vec3 start = 0.5 * (o.start_lo_m + o.start_hi_m);  // the middle of where its shot start
        for (const Component& c : m.components) {
            if (c.role == ComponentRole::chamber || !c.edges.closed()) continue;
            const Inside inside = inside_component(c, start);
            if (inside == Inside::no) continue;
            out.push_back({true, m.description.sources[s].where, "sources[" + std::to_string(s) + "]",
                           "the " + o.start_place + " of " + o.kind + " '" + m.sources[s]->name() + "' at " + mm_point(start) +
                               " lies inside '" + c.name + "'" + (inside == Inside::as_it_turns ? " as it turns" : "") +
                               ": every shot would start inside it; expected an " + o.start_place + " in the open (check " + o.start_keys +
                               ")",
                           start});
        }
    }
    return out;
}

}  // namespace peensim
