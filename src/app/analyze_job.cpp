#include "app/analyze_job.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>

#include "analysis/impact_stream.h"
#include "analysis/part_coverage.h"
#include "app/analysis_figures.h"
#include "app/analysis_plots.h"
#include "app/analysis_report.h"
#include "app/analysis_tables.h"
#include "app/component_analysis.h"
#include "app/map_smoothing.h"
#include "app/report_errors.h"
#include "contact/dent.h"
#include "geometry/mesh_checks.h"
#include "geometry/mesh_loader.h"
#include "output/atomic_file.h"
#include "output/impact_csv_writer.h"
#include "scene/scene_parser.h"
#include "scene/shot_mix.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

constexpr int kCoverageSamples = 50;       // points of the coverage- and dose-vs-time curves
constexpr std::uint64_t kJetWindow = 500;  // impacts per window of the jet's figures

const MaterialDesc* material_named(const SceneDescription& scene, const std::string& name) {
    for (const MaterialDesc& m : scene.materials)
        if (m.name == name) return &m;
    return nullptr;
}

// Simulated time the log covers: from summary.json, or the scene's duration.
double simulated_time(const fs::path& dir, const SceneDescription& scene, bool& finished) {
    finished = fs::exists(dir / kImpactCsvFileName);
    std::ifstream in(dir / "summary.json");
    if (in) {
        try {
            const auto j = nlohmann::json::parse(in);
            if (j.contains("simulated_time_s")) return j["simulated_time_s"].get<double>();
        } catch (const std::exception&) {}
    }
    return scene.process.duration_s;
}

// Which regions hold each triangle, as compressed rows (a triangle may be in several regions).
void index_regions(ComponentAnalysis& a) {
    const std::size_t n = a.mesh->triangle_count();
    std::vector<std::vector<std::uint32_t>> of(n);
    for (std::size_t r = 0; r < a.regions.size(); ++r)
        for (int t : a.regions[r].triangles) of[static_cast<std::size_t>(t)].push_back(static_cast<std::uint32_t>(r));
    a.region_start.assign(n + 1, 0);
    for (std::size_t t = 0; t < n; ++t) {
        a.region_start[t + 1] = a.region_start[t] + static_cast<std::uint32_t>(of[t].size());
        a.region_index.insert(a.region_index.end(), of[t].begin(), of[t].end());
    }
    a.region_histograms.assign(a.regions.size(), ImpactHistograms{});
}

ComponentAnalysis analysis_of(const ComponentDesc& c, const SceneDescription& scene, double shot_mass) {
    ComponentAnalysis a;
    a.name = c.name;
    a.role = c.role;
    a.mesh = std::make_unique<TriangleMesh>(load_mesh(c.mesh_path, c.mesh_unit_m));
    a.fields = std::make_unique<TriangleFields>(*a.mesh, shot_mass);
    a.regions = select_regions(*a.mesh, c.regions);
    index_regions(a);
    const MaterialDesc* m = material_named(scene, c.material);
    if (m && m->yield_stress_pa) {
        a.yield_stress_pa = *m->yield_stress_pa;
        a.coverage = part_coverage_map(*a.mesh, smallest_diameter_m(scene.shot), largest_diameter_m(scene.shot),
                                       scene.shot.density_kg_per_m3, a.yield_stress_pa);
    }
    if (c.almen) {
        AlmenAnalysis almen;
        try {
            almen.dose = std::make_unique<AlmenDose>(*a.mesh, c.almen->face_normal, shot_mass);
        } catch (const std::invalid_argument& e) {
            throw InputError(c.almen->where, "almen.face_normal",
                             std::string(e.what()) +
                                 " (expected the outward normal of "
                                 "one face of the strip, in the component's frame)");
        }
        if (c.almen->saturation_arc_height_m)
            almen.calibration = AlmenCalibration{*c.almen->saturation_arc_height_m, *c.almen->dose_constant_J_per_m2};
        a.almen = std::move(almen);
    }
    if (!scene.sources.empty()) {
        // Several nozzles: their exit speeds and axes weighted by their rates.
        double rate = 0.0, v0 = 0.0;
        Vec3 axis = Vec3::Zero();
        for (const SourceDesc& s : scene.sources) {
            rate += s.rate_per_s;
            v0 += s.rate_per_s * s.speed_m_per_s;
            axis += s.rate_per_s * s.direction;
        }
        if (rate > 0.0 && v0 > 0.0) {
            a.jet.emplace(v0 / rate, kJetWindow);
            a.jet_axis = (c.rotation.transpose() * axis).normalized();  // world -> component frame
            a.jet_normal_meaningful = scene.sources.size() == 1 && !c.rotation_motion;
        }
    }
    return a;
}

// Adds one impact row to a component's statistics (the ParaView points are written by the reader thread).
void accumulate(ComponentAnalysis& a, const ImpactRow& row, const SceneDescription& scene, double duration) {
    // The impacting shot: a mix's log names its diameter, a log of one size has that size.
    const double D = row.shot_diameter_m > 0.0 ? row.shot_diameter_m : scene.shot.sizes.front().diameter_m;
    if (row.shot_diameter_m == 0.0 && scene.shot.sizes.size() > 1)
        throw std::runtime_error("the scene has a shot mix but its impact log has no shot_diameter_m column: was it written by this run?");
    const double mass = sphere_mass_kg(D, scene.shot.density_kg_per_m3);
    const int t = a.fields->add(row.triangle, row.point_m, row.vn_in_m_per_s, mass);
    smooth_impact(a, row, t, mass);
    ++a.impacts;
    a.speed_sum += row.vn_in_m_per_s;
    const auto batch =
        static_cast<std::size_t>(std::clamp(static_cast<int>(row.time_s / duration * kFigureBatches), 0, kFigureBatches - 1));
    ++a.batch_impacts[batch];
    a.batch_speed_sum[batch] += row.vn_in_m_per_s;
    double dent = std::numeric_limits<double>::quiet_NaN();
    if (a.coverage) {
        dent = dent_diameter(D, scene.shot.density_kg_per_m3, row.vn_in_m_per_s, a.yield_stress_pa);
        a.coverage->add_dent(row.point_m, dent);
        a.dent_sum += dent;
    }
    a.histograms.add(row.vn_in_m_per_s, row.vt_in_m_per_s, dent);
    if (t >= 0) {
        const auto ti = static_cast<std::size_t>(t);
        for (std::uint32_t k = a.region_start[ti]; k < a.region_start[ti + 1]; ++k)
            a.region_histograms[a.region_index[k]].add(row.vn_in_m_per_s, row.vt_in_m_per_s, dent);
    }
    if (a.almen) a.almen->dose->add(t, row.vn_in_m_per_s, mass);
    if (row.shot_diameter_m > 0.0) {
        auto size = std::find_if(a.sizes.begin(), a.sizes.end(), [&](const ComponentAnalysis::SizeTally& z) { return z.diameter_m == D; });
        if (size == a.sizes.end()) size = a.sizes.insert(a.sizes.end(), ComponentAnalysis::SizeTally{D});
        ++size->impacts;
        size->speed_sum += row.vn_in_m_per_s;
        if (a.coverage) size->dent_sum += dent;
        size->energy_J += 0.5 * mass * row.vn_in_m_per_s * row.vn_in_m_per_s;
    }
    if (a.jet) {
        const double jet_normal =
            t >= 0 ? a.jet->v0_m_per_s() * std::abs(a.jet_axis.dot(triangle_normal(*a.mesh, static_cast<std::size_t>(t)))) : 0.0;
        a.jet->add(row.time_s, row.v_in_m_per_s.norm(), row.vn_in_m_per_s, jet_normal);
    }
}

// What the report takes from the run's summary.json, when it has it.
void read_flow_figures(const fs::path& dir, ReportContext& context) {
    std::ifstream in(dir / "summary.json");
    if (!in) return;
    try {
        const auto j = nlohmann::json::parse(in);
        for (const auto& c : j.value("impacts_per_component", nlohmann::json::array()))
            if (c.value("component", "") == "shot-shot") context.shot_shot_impacts = c.value("impacts", std::uint64_t{0});
        for (const auto& e : j.value("flow_rate_eps", nlohmann::json::array()))
            context.flow_rate_eps.emplace_back(e.value("source", ""), e.value("eps", 0.0));
    } catch (const std::exception&) {}  // an older or damaged summary: the report goes without
}

}  // namespace

int analyze_job(const std::string& output_dir, std::ostream& out, std::ostream& err, const AnalyzeOptions& options) {
    return report_errors(err, [&] {
        analyze_run(output_dir, out, err, options);
        return 0;
    });
}

void analyze_run(const std::string& output_dir, std::ostream& out, std::ostream& err, const AnalyzeOptions& options) {
    const fs::path dir(output_dir);
    const fs::path scene_path = dir / "scene.resolved.yaml";
    if (!fs::exists(scene_path)) throw std::runtime_error(output_dir + ": not a peensim run directory (no scene.resolved.yaml)");
    const SceneDescription scene = parse_scene_file(scene_path.string());
    bool finished = false;
    const double duration = simulated_time(dir, scene, finished);
    const fs::path log = finished ? dir / kImpactCsvFileName : dir / kImpactCsvPartialFileName;
    if (!fs::exists(log)) throw std::runtime_error(output_dir + ": no impact log (impacts.csv or impacts.csv.partial)");
    if (!finished) err << "note: " << output_dir << ": the run did not finish; analysing its partial impact log\n";

    // Components whose impacts were logged.
    std::vector<ComponentAnalysis> parts;
    std::vector<std::string> names;
    const double shot_mass = mean_shot_mass_kg(scene.shot);  // each impact brings its own (accumulate)
    for (const ComponentDesc& c : scene.components) {
        if (!is_logged(scene, c)) continue;
        parts.push_back(analysis_of(c, scene, shot_mass));
        start_smoothing(parts.back(), scene, c, dir, options.smoothing_radius);
        names.push_back(c.name);
    }
    if (parts.empty())
        throw std::runtime_error(output_dir + ": the run logged no component (output.log is empty and the scene has no part)");

    const fs::path adir = dir / "analysis";
    fs::create_directories(adir);
    for (ComponentAnalysis& a : parts)
        a.points = std::make_unique<ImpactPointsVtpWriter>((adir / (a.name + "_impacts.vtp")).string(), impact_point_field_layouts());

    int next_sample = 1;
    auto sample_until = [&](double t) {
        while (next_sample <= kCoverageSamples && t >= duration * next_sample / kCoverageSamples) {
            const double at = duration * next_sample / kCoverageSamples;
            for (ComponentAnalysis& a : parts) {
                if (a.coverage) a.curve.push_back({at, a.coverage->coverage()});
                if (a.almen) a.almen->curve.push_back({at, a.almen->dose->dose_J_per_m2()});
            }
            ++next_sample;
        }
    };
    for (ComponentAnalysis& a : parts) {
        if (a.coverage) a.curve.push_back({0.0, 0.0});
        if (a.almen) a.almen->curve.push_back({0.0, 0.0});
    }
    // The reader thread parses the log and writes the ParaView points; this one does the rest.
    ImpactStream stream(log.string(), names, [&parts](const ImpactRow& row, int component) {
        const double values[5] = {row.v_in_m_per_s.x(), row.v_in_m_per_s.y(), row.v_in_m_per_s.z(), row.vn_in_m_per_s, row.time_s};
        parts[static_cast<std::size_t>(component)].points->add(row.point_m, values);
    });
    for (auto block = stream.next_block(); !block.empty(); block = stream.next_block()) {
        for (const IndexedImpact& impact : block) {
            sample_until(impact.row.time_s);
            if (impact.component >= 0) accumulate(parts[static_cast<std::size_t>(impact.component)], impact.row, scene, duration);
        }
    }
    sample_until(duration);

    for (ComponentAnalysis& a : parts) {
        a.points->finish();
        finish_smoothing(a);
        write_component_tables(adir, a, duration);
    }
    ReportContext context{dir, duration, finished, stream.truncated(), {}, "", {}, {}};
    read_flow_figures(dir, context);
    context.pngs = write_analysis_plots(adir.string(), names, context.plot_note);
    write_file_atomically((adir / "report.md").string(), analysis_report(scene, parts, context));
    write_file_atomically((adir / "figures.json").string(), analysis_figures_json(parts, duration));
    out << analysis_summary_table(parts, duration) << "analysis: " << adir.string()
        << "/{report.md, *_triangles.csv, *_coverage.csv, *_histograms.csv, *.vtp, *_impacts.vtp" << (context.pngs.empty() ? "" : ", *.png")
        << "}\n";
    for (const ComponentAnalysis& a : parts) out << smoothing_note(a) << '\n';
}

}  // namespace peensim
