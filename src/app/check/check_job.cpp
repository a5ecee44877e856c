#include "app/check/check_job.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <ostream>
#include <sstream>

#include "app/check/setup_checks.h"
#include "app/exit_codes.h"
#include "app/render_module.h"
#include "app/report_errors.h"
#include "common/input_error.h"
#include "engine/time_stepping.h"
#include "model/assembly_checks.h"
#include "model/model.h"
#include "model/shot_placement.h"
#include "output/output_names.h"
#include "scene/scene_parser.h"

namespace peensim {

namespace {

std::string fixed_mm(double m) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(3) << m * 1e3;
    return s.str();
}

void print_assembly(const Model& model, const AssemblyReport& report, std::ostream& out) {
    out << "# assembly at t = 0 (world frame, mm):\n";
    for (std::size_t i = 0; i < model.components.size(); ++i) {
        const Component& c = model.components[i];
        const ComponentFacts& f = report.components[i];
        // As placed at t = 0 (its real size); a turning part's swept solid on a line of its own.
        const Vec3 size = f.rest_hi - f.rest_lo;
        out << "#   " << std::left << std::setw(14) << c.name << std::setw(10) << role_name(c.role) << std::right << " from ("
            << fixed_mm(f.rest_lo.x()) << ", " << fixed_mm(f.rest_lo.y()) << ", " << fixed_mm(f.rest_lo.z()) << ") to ("
            << fixed_mm(f.rest_hi.x()) << ", " << fixed_mm(f.rest_hi.y()) << ", " << fixed_mm(f.rest_hi.z()) << "), size "
            << fixed_mm(size.x()) << " x " << fixed_mm(size.y()) << " x " << fixed_mm(size.z()) << ", " << f.triangles << " triangles, "
            << (f.closed ? "closed" : "open") << "\n";
        if (std::isfinite(f.swept_radius_m)) {
            const Vec3 swept = f.swept_hi - f.swept_lo;
            out << "#   " << std::setw(24) << ""
                << " swept in a turn: from (" << fixed_mm(f.swept_lo.x()) << ", " << fixed_mm(f.swept_lo.y()) << ", "
                << fixed_mm(f.swept_lo.z()) << ") to (" << fixed_mm(f.swept_hi.x()) << ", " << fixed_mm(f.swept_hi.y()) << ", "
                << fixed_mm(f.swept_hi.z()) << "), " << fixed_mm(swept.x()) << " x " << fixed_mm(swept.y()) << " x " << fixed_mm(swept.z())
                << ", radius " << fixed_mm(f.swept_radius_m) << " about its axis\n";
        }
        if (std::isfinite(f.reachable_fraction))
            out << "#   " << std::setw(24) << ""
                << " clearance to the sonotrode (less A0) " << fixed_mm(f.clearance_to_sonotrode_m) << ", to the chamber "
                << fixed_mm(f.clearance_to_chamber_m) << "; shot reach " << std::setprecision(0) << std::fixed
                << 100.0 * f.reachable_fraction << " % of its surface\n"
                << std::defaultfloat << std::setprecision(6);
        if (c.kinematics.kind == Kinematics::Kind::vibrating)
            out << "#   " << std::setw(24) << ""
                << " vibrates along (" << c.kinematics.axis.x() << ", " << c.kinematics.axis.y() << ", " << c.kinematics.axis.z()
                << "), A0 " << c.kinematics.amplitude_m * 1e6 << " um, " << c.kinematics.frequency_hz * 1e-3 << " kHz\n";
        if (c.kinematics.kind == Kinematics::Kind::rotating) {
            const Vec3& p = c.kinematics.axis_point_m;
            const Vec3& u = c.kinematics.axis_direction;
            out << "#   " << std::setw(24) << ""
                << " turns about the axis through (" << fixed_mm(p.x()) << ", " << fixed_mm(p.y()) << ", " << fixed_mm(p.z()) << ") along ("
                << u.x() << ", " << u.y() << ", " << u.z() << ") at " << c.kinematics.omega_rad_per_s * 30.0 / M_PI << " rpm\n";
        }
    }
}

void print_report(const Model& model, const AssemblyReport& assembly, std::size_t warnings, const InitialShots& shots, std::ostream& out) {
    out << "# peensim check: the scene is valid"
        << (warnings ? " (with " + std::to_string(warnings) + " warning(s), above)" : std::string()) << ".\n";
    out << "# components:\n";
    for (const Component& c : model.components) {
        out << "#   " << std::left << std::setw(14) << c.name << std::setw(10) << role_name(c.role) << std::right << std::setw(8)
            << c.mesh->triangle_count() << " triangles, contact '" << c.coefficients_source << "'" << (c.logged ? ", impacts logged" : "")
            << "\n";
    }
    print_assembly(model, assembly, out);
    const double dt_rest = TimeStepping::time_step(model, model.peak_surface_speed_m_per_s);
    if (model.sonotrode >= 0) out << "# shot: " << model.shot_count << " placed in " << shots.layers << " layer(s) on the sonotrode\n";
    for (const auto& source : model.sources) {
        const SourceOutline o = source->outline();
        out << "# source " << source->name() << " (" << o.kind << "): " << o.rate_per_s << " shot/s " << o.how << ", from " << o.start_s
            << " s to " << o.stop_s << " s (" << static_cast<long long>(std::ceil((o.stop_s - o.start_s) * o.rate_per_s))
            << " shot at most)\n";
    }
    for (const auto& sink : model.sinks) out << "# sink " << sink->name() << "\n";
    out << "# fastest surface: " << model.peak_surface_speed_m_per_s << " m/s; eq. 7 step with still shot: " << dt_rest * 1e6
        << " us (shorter while shot fly faster)\n";
    out << "# resolved scene (SI units):\n";
    out << model.resolved_scene_yaml;
}

}  // namespace

std::size_t check_scene(const std::string& scene_path, const std::optional<std::string>& scene_text,
                        const std::vector<std::string>& overrides, bool strict, std::ostream& out, std::ostream& err,
                        const std::string& picture_png) {
    if (!picture_png.empty()) check_output_file_directory("--render", picture_png);
    const SceneDescription scene = parse_scene(scene_path, scene_text, overrides);
    const auto model = compile_model(scene);
    // The picture is drawn whatever the checks find: a misplaced part is what it is for.
    // The issues that name a point (two meshes crossing) are marked in it.
    std::vector<AssemblyIssue> issues;
    const auto draw = [&](const std::vector<Vec3>& shot_positions, const char* what) {
        if (picture_png.empty()) return;
        SimulationState start;
        start.shots.resize(shot_positions.size());
        for (std::size_t i = 0; i < shot_positions.size(); ++i) start.shots.set_position(i, shot_positions[i]);
        render_module().draw_assembly(*model, start, issues, picture_png, 1280, 720);
        const auto marked = std::count_if(issues.begin(), issues.end(), [](const AssemblyIssue& i) { return i.at_m.has_value(); });
        out << "# picture of the assembly" << what << ": " << picture_png
            << (marked ? " (" + std::to_string(marked) + " point(s) marked where meshes cross)" : std::string()) << "\n";
    };
    std::optional<SetupCheck> setup;
    InitialShots shots;
    try {
        setup.emplace(check_setup(*model, strict, err, &issues));
        if (setup->cavity) shots = place_shots(*model, *setup->cavity, setup->rng);
    } catch (const InputError&) {
        draw({}, " (without shot: the setup has an error)");
        throw;
    }
    print_report(*model, setup->assembly, setup->warnings, shots, out);
    draw(shots.positions, "");
    return setup->warnings;
}

int check_job(const std::string& scene_path, const std::vector<std::string>& overrides, bool strict, std::ostream& out, std::ostream& err,
              const std::string& picture_png) {
    return report_errors(err, [&] {
        check_scene(scene_path, std::nullopt, overrides, strict, out, err, picture_png);
        return static_cast<int>(kExitOk);
    });
}

}  // namespace peensim
