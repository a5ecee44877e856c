#include "model/plausibility.h"

#include <cmath>
#include <sstream>

#include "common/cad_file.h"
#include "model/shot_cavity.h"

namespace peensim {

namespace {

std::string short_number(double v) {
    std::ostringstream s;
    s.precision(4);
    s << v;
    return s.str();
}

// The sonotrode's vibration against ultrasonic peening's window.
template <class Warn>
void sonotrode_issues(const Model& m, std::size_t sono, Warn&& warn) {
    const SceneDescription& scene = m.description;
    const Kinematics& vib = m.components[sono].kinematics;
    const SourceLocation& sono_where = scene.components[sono].where;
    // A hint only where the slip is plain: the number meant in the usual unit lands in the window.
    if (vib.amplitude_m > 1e-3) {
        const bool in_um = vib.amplitude_m * 1e-6 >= 1e-6 && vib.amplitude_m * 1e-6 <= 1e-3;
        warn(sono_where, component_field(sono) + ".vibration.amplitude",
             "A0 " + short_number(vib.amplitude_m * 1e3) + " mm is far above ultrasonic peening's 10-100 um" +
                 (in_um ? "; did you mean " + short_number(vib.amplitude_m) + " um?" : std::string()));
    }
    if (vib.frequency_hz > 0.0 && (vib.frequency_hz < 1e3 || vib.frequency_hz > 1e5)) {
        const auto in_window = [](double f) { return f >= 1e3 && f <= 1e5; };
        std::string hint;
        if (in_window(vib.frequency_hz * 1e3))
            hint = "; did you mean " + short_number(vib.frequency_hz) + " kHz?";
        else if (in_window(vib.frequency_hz * 1e-3))
            hint = "; did you mean " + short_number(vib.frequency_hz * 1e-3) + " Hz?";
        warn(sono_where, component_field(sono) + ".vibration.frequency",
             short_number(vib.frequency_hz) + " Hz is outside 1-100 kHz (ultrasonic sonotrodes run at ~20 kHz)" + hint);
    }
}

// A rotating part's rim speed (its farthest point from the axis): peening fixtures turn parts at a
// few m/s at most, and no part survives a rim at 1000 m/s (the fastest shot a nozzle throws, the
// schema's limit on sources[].speed); 1e9 rpm made a run crawl without a word.
template <class Issue>
void rotation_issues(const Model& m, std::size_t i, Issue&& issue) {
    const Component& c = m.components[i];
    const Kinematics& k = c.kinematics;
    if (k.kind != Kinematics::Kind::rotating || k.omega_rad_per_s == 0.0) return;
    const double radius_m = c.max_axis_distance_m;
    const double rim_m_per_s = std::abs(k.omega_rad_per_s) * radius_m;
    if (!(rim_m_per_s > kPlausibleRimSpeed_m_per_s)) return;
    const double rpm = std::abs(k.omega_rad_per_s) * 60.0 / (2.0 * M_PI);
    issue(rim_m_per_s > kLargestRimSpeed_m_per_s, m.description.components[i].where, component_field(i) + ".motion.speed",
          short_number(rpm) + " rpm puts the rim of '" + c.name + "' (" + short_number(radius_m * 1e3) + " mm from the axis) at " +
              short_number(rim_m_per_s) + " m/s: " +
              (rim_m_per_s > kLargestRimSpeed_m_per_s
                   ? "expected at most " + short_number(kLargestRimSpeed_m_per_s) + " m/s (no part survives it)"
                   : "peening turns parts at a few m/s") +
              "; a plain number is rad/s (e.g. speed: \"30 rpm\")");
}

// The shot's start speed: ultrasonic shot fly at 1-20 m/s.
template <class Warn>
void start_speed_issues(const Model& m, Warn&& warn) {
    const ShotDesc& shot = m.description.shot;
    const bool vector = shot.initial == InitialVelocityKind::vector;
    const double v = vector ? shot.initial_velocity_m_per_s.norm() : shot.initial_speed_m_per_s;
    if (shot.initial == InitialVelocityKind::rest || !(v > kPlausibleStartSpeed_m_per_s)) return;
    warn(shot.where, vector ? "shot.initial_velocity" : "shot.initial_speed",
         "shot start at " + short_number(v) +
             " m/s: far above ultrasonic peening's 1-20 m/s (the sonotrode sets their speed within a few impacts)");
}

}  // namespace

std::vector<AssemblyIssue> plausibility_issues(const Model& m) {
    std::vector<AssemblyIssue> out;
    const SceneDescription& scene = m.description;
    auto warn = [&](const SourceLocation& where, std::string field, std::string message) {
        out.push_back({false, where, std::move(field), std::move(message), std::nullopt});
    };
    for (const SceneDescription::Warning& w : scene.warnings) warn(w.where, w.field, w.message);

    auto issue = [&](bool error, const SourceLocation& where, std::string field, std::string message) {
        out.push_back({error, where, std::move(field), std::move(message), std::nullopt});
    };
    for (std::size_t k = 0; k < m.components.size(); ++k) {
        if (m.components[k].role == ComponentRole::sonotrode) sonotrode_issues(m, k, warn);
        rotation_issues(m, k, issue);
    }
    start_speed_issues(m, warn);
    // The chamber: the union of the chamber components' bounds.
    Vec3 lo = Vec3::Constant(1e300), hi = -lo;
    for (const Component& c : m.components)
        if (c.role == ComponentRole::chamber) lo = lo.cwiseMin(c.world_lo), hi = hi.cwiseMax(c.world_hi);
    const Vec3 chamber = hi - lo;
    const double D = 2.0 * m.max_shot_radius_m;            // the largest of a mix
    if (lo.x() <= hi.x() && D > 0.1 * chamber.minCoeff())  // (a scene fed by sources may have no chamber)
        warn(scene.shot.where, scene.shot.sizes_given ? "shot.sizes" : "shot.diameter",
             "shot of " + short_number(D * 1e3) + " mm in a chamber " + short_number(chamber.minCoeff() * 1e3) +
                 " mm across at its narrowest: more than a tenth of it; check shot.diameter and the chamber's mesh_unit");

    const double g = m.gravity_m_per_s2.norm();
    if (g != 0.0 && std::abs(g - 9.81) > 0.1)
        warn(scene.process.where, "process.gravity",
             short_number(g) + " m/s2: expected ~9.81 m/s2 (or zero for a weightless test); gravity is in m/s2");

    for (std::size_t i = 0; i < m.components.size(); ++i) {
        const Component& c = m.components[i];
        const ComponentDesc& desc = scene.components[i];
        if (is_cad_file(desc.mesh_path)) continue;  // read in the unit the file states: there is no mesh_unit to have slipped
        Vec3 clo = Vec3::Constant(1e300), chi = -clo;
        for (const Vec3& v : c.mesh->vertices) clo = clo.cwiseMin(v), chi = chi.cwiseMax(v);
        const double size = (chi - clo).maxCoeff();  // m, in the component's own frame (not swept)
        const std::string unit_now = short_number(desc.mesh_unit_m) + " m per file unit";
        const std::string field = component_field(i) + ".mesh_unit";
        if (size > kLargestPlausibleMesh_m) {
            const double mm = size / desc.mesh_unit_m * 1e-3;
            warn(desc.where, field,
                 "'" + c.name + "' is " + short_number(size) + " m across (" + unit_now + "): implausible for a peening chamber" +
                     (mm <= kLargestPlausibleMesh_m && mm >= kSmallestPlausibleMesh_m
                          ? "; in mm it would be " + short_number(mm * 1e3) + " mm (mesh_unit: mm)"
                          : std::string()));
        } else if (size < kSmallestPlausibleMesh_m) {
            const double in_mm = size / desc.mesh_unit_m * 1e-3;
            warn(desc.where, field,
                 "'" + c.name + "' is " + short_number(size * 1e3) + " mm across (" + unit_now + "): implausibly small" +
                     (in_mm >= kSmallestPlausibleMesh_m ? "; in mm it would be " + short_number(in_mm * 1e3) + " mm (mesh_unit: mm)"
                                                        : std::string()));
        } else if ((c.role == ComponentRole::part || c.role == ComponentRole::fixture) && size < chamber.maxCoeff() / 20.0 &&
                   size * 25.4 <= chamber.maxCoeff() && desc.mesh_unit_m == 1e-3) {
            warn(desc.where, field,
                 "'" + c.name + "' is " + short_number(size * 1e3) + " mm across, small beside the chamber (" +
                     short_number(chamber.maxCoeff() * 1e3) + " mm): if the file is in inches, set mesh_unit: in (" +
                     short_number(size * 25.4 * 1e3) + " mm)");
        }
    }
    return out;
}

}  // namespace peensim
