#include "app/check_job.h"

#include <iomanip>
#include <ostream>

#include "app/report_errors.h"
#include "app/run_job.h"
#include "common/input_error.h"
#include "engine/time_stepping.h"
#include "model/model.h"
#include "model/shot_placement.h"
#include "scene/scene_parser.h"

namespace peensim {

namespace {


void print_report(const Model& model, const InitialShots& shots, std::ostream& out) {
    out << "# peensim check: the scene is valid.\n";
    out << "# components:\n";
    for (const Component& c : model.components) {
        out << "#   " << std::left << std::setw(14) << c.name << std::setw(10) << role_name(c.role) << std::right
            << std::setw(8) << c.mesh->triangle_count() << " triangles, contact '" << c.coefficients_source << "'"
            << (c.logged ? ", impacts logged" : "") << "\n";
    }
    const double dt_rest = TimeStepping::time_step(model, model.peak_surface_speed_m_per_s);
    out << "# shot: " << model.shot_count << " placed in " << shots.layers << " layer(s) on the sonotrode\n";
    out << "# fastest surface: " << model.peak_surface_speed_m_per_s << " m/s; eq. 7 step with still shot: " << dt_rest * 1e6
        << " us (shorter while shot fly faster)\n";
    out << "# resolved scene (SI units):\n";
    out << model.resolved_scene_yaml;
}

}  // namespace

int check_job(const std::string& scene_path, const std::vector<std::string>& overrides, std::ostream& out, std::ostream& err) {
    return report_errors(err, [&] {
        const SceneDescription scene = parse_scene_file(scene_path, overrides);
        const auto model = compile_model(scene);
        const InitialShots shots = place_shots(*model);
        print_report(*model, shots, out);
        return static_cast<int>(kExitOk);
    });
}

}  // namespace peensim
