#include "support/sonotrode_crossing.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace peensim::testing {

namespace {
constexpr double kSameState_m = 1e-12;       // m, end position equal to the free flight's
constexpr double kSameState_m_per_s = 1e-9;  // m/s, end velocity equal to the free flight's
}  // namespace

SonotrodeCrossingCheck::SonotrodeCrossingCheck(const Model& model, double plate_top_m, double tolerance_m, double samples_per_period)
    : model_(model), plate_top_m_(plate_top_m), tolerance_m_(tolerance_m), samples_per_period_(samples_per_period) {}

void SonotrodeCrossingCheck::before_step(const SimulationState& state) {
    before_ = state.shots;
    t0_ = state.time;
}

void SonotrodeCrossingCheck::after_step(const SimulationState& state, const std::vector<ImpactRecord>& impacts) {
    const std::size_t n = before_.size();
    const Kinematics& kin = model_.sonotrode_component().kinematics;
    const Vec3 g = model_.gravity_m_per_s2;
    const double dt = (state.time.hi - t0_.hi) + (state.time.lo - t0_.lo);
    last_impact_.assign(n, -1);
    for (std::size_t k = 0; k < impacts.size(); ++k) {
        const auto shot = static_cast<std::size_t>(impacts[k].shot);
        const int previous = last_impact_[shot];
        if (previous < 0 || impacts[k].time_s >= impacts[static_cast<std::size_t>(previous)].time_s)
            last_impact_[shot] = static_cast<int>(k);
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (!before_.active[i] || !state.shots.active[i]) continue;
        const double R = model_.shot_sizes[state.shots.size_class[i]].radius_m;  // this shot's
        // The flight's start: offset u0 (s) into the step, centre c (m), velocity v (m/s).
        double u0 = 0.0;
        Vec3 c = before_.position(i), v = before_.velocity(i);
        if (last_impact_[i] >= 0) {
            const ImpactRecord& r = impacts[static_cast<std::size_t>(last_impact_[i])];
            if (r.component != model_.sonotrode) continue;  // after an impact elsewhere: not checked
            u0 = (r.time_s - t0_.hi) - t0_.lo;
            const Pose pose = kin.pose(t0_, u0);
            c = pose.to_world(r.point_m) + R * Vec3::UnitZ();
            v = pose.rotation * r.v_out_m_per_s + kin.point_velocity(c, t0_, u0);
        }
        const double s_end = dt - u0;
        const Vec3 c_end = c + v * s_end + 0.5 * g * s_end * s_end, v_end = v + g * s_end;
        if ((state.shots.position(i) - c_end).norm() > kSameState_m || (state.shots.velocity(i) - v_end).norm() > kSameState_m_per_s)
            continue;  // something else acted on the shot in this step
        ++report_.flights_checked;
        double deepest = 0.0, at = 0.0;
        const int samples = std::max(8, static_cast<int>(std::ceil(s_end * kin.frequency_hz * samples_per_period_)));
        for (int k = 1; k < samples; ++k) {
            const double s = s_end * k / samples;
            const double z = c.z() + v.z() * s + 0.5 * g.z() * s * s;
            const double gap = z - R - (plate_top_m_ + kin.displacement(t0_, u0 + s));
            if (gap < deepest) deepest = gap, at = s;
        }
        if (deepest >= -tolerance_m_) continue;
        ++report_.missed_contacts;
        report_.deepest_m = std::min(report_.deepest_m, deepest);
        if (report_.first_example.empty()) {
            std::ostringstream e;
            e.precision(10);
            e << "shot " << i << ", step from t0 = " << t0_.seconds() << " s, dt = " << dt << " s; flight from u0 = " << u0
              << " s: centre z = " << c.z() << " m, vz = " << v.z() << " m/s; plate at u0: z = " << plate_top_m_ + kin.displacement(t0_, u0)
              << " m, vz = " << kin.displacement_rate(t0_, u0)
              << " m/s; step end: gap = " << state.shots.z[i] - R - (plate_top_m_ + kin.displacement(t0_, dt)) << " m; deepest gap "
              << deepest << " m at u = " << u0 + at << " s";
            report_.first_example = e.str();
        }
    }
}

}  // namespace peensim::testing
