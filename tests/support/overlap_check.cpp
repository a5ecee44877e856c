#include "support/overlap_check.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace peensim::testing {

OverlapAudit::OverlapAudit(const Model& model, double tolerance_m) : model_(model), tolerance_m_(tolerance_m) {}

void OverlapAudit::audit(const SimulationState& state) {
    ++report_.audits;
    const ShotArrays& s = state.shots;
    const std::size_t n = s.size();
    // Each shot's own radius (a mix has several).
    const auto radius = [&](std::size_t i) { return model_.shot_sizes[s.size_class[i]].radius_m; };
    for (std::size_t i = 0; i < n; ++i) {
        if (!s.active[i]) continue;
        for (std::size_t j = i + 1; j < n; ++j) {
            if (!s.active[j]) continue;
            const double dx = s.x[i] - s.x[j], dy = s.y[i] - s.y[j], dz = s.z[i] - s.z[j];
            const double d2 = dx * dx + dy * dy + dz * dz;
            const double touch = radius(i) + radius(j);
            if (d2 > 4.0 * touch * touch) continue;  // far apart: not a candidate for the worst gap
            const double gap = std::sqrt(d2) - touch;
            const bool worst = gap < report_.worst_pair_gap_m;
            report_.worst_pair_gap_m = std::min(report_.worst_pair_gap_m, gap);
            if (gap >= -tolerance_m_) continue;
            ++report_.pair_overlaps;
            if (report_.first_pair.empty() || worst) {
                std::ostringstream e;
                e.precision(12);
                e << "t = " << state.time.seconds() << " s: shot " << i << " at " << s.position(i).transpose() << " m, "
                  << s.velocity(i).transpose() << " m/s and " << j << " at " << s.position(j).transpose() << " m, "
                  << s.velocity(j).transpose() << " m/s: gap " << gap << " m";
                if (report_.first_pair.empty()) report_.first_pair = e.str();
                if (worst) report_.worst_pair = e.str();
            }
        }
    }
    for (const Component& c : model_.components) {
        const Pose pose = c.kinematics.pose(state.time);
        for (std::size_t i = 0; i < n; ++i) {
            if (!s.active[i]) continue;
            const double R = radius(i);
            MeshCollider::Closest closest;
            MeshCollider::QueryCounters counters;
            // Within 2R, so that the closest approach is reported even without an overlap.
            if (!c.collider->closest_within(pose.to_component(s.position(i)), 2.0 * R, closest, counters)) continue;
            const double gap = closest.distance - R;
            const bool worst = gap < report_.worst_mesh_gap_m;
            report_.worst_mesh_gap_m = std::min(report_.worst_mesh_gap_m, gap);
            if (gap >= -tolerance_m_) continue;
            ++report_.mesh_overlaps;
            if (report_.first_mesh.empty() || worst) {
                std::ostringstream e;
                e.precision(12);
                e << "t = " << state.time.seconds() << " s: shot " << i << " at " << s.position(i).transpose() << " m, "
                  << s.velocity(i).transpose() << " m/s, component " << c.name << " triangle " << closest.triangle << ": gap " << gap
                  << " m";
                if (report_.first_mesh.empty()) report_.first_mesh = e.str();
                if (worst) report_.worst_mesh = e.str();
            }
        }
    }
}

std::string OverlapAudit::summary() const {
    std::ostringstream o;
    o << report_.audits << " states audited; shot pairs: " << report_.pair_overlaps << " overlaps, worst gap " << report_.worst_pair_gap_m
      << " m; meshes: " << report_.mesh_overlaps << " overlaps, worst gap " << report_.worst_mesh_gap_m << " m";
    return o.str();
}

}  // namespace peensim::testing
