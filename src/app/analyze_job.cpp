#include "app/analyze_job.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>

#include "analysis/avrami.h"
#include "analysis/coverage_map.h"
#include "analysis/dent.h"
#include "analysis/impact_log_reader.h"
#include "analysis/region_stats.h"
#include "analysis/regions.h"
#include "analysis/triangle_fields.h"
#include "app/analysis_plots.h"
#include "app/report_errors.h"
#include "geometry/mesh_loader.h"
#include "output/atomic_file.h"
#include "output/impact_csv_writer.h"
#include "output/vtp_writer.h"
#include "scene/scene_parser.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

constexpr int kCoverageSamples = 50;           // points of the coverage-vs-time curve
constexpr double kDentsPerSpacing = 5.0;       // coverage sampling: spacing = dent at 1 m/s / 5
constexpr double kLargestSpeed = 30.0;         // m/s, sizes the coverage map's dent grid
constexpr double kMaxSamples = 5.0e7;          // coverage samples per component at most (memory ~ 1 byte each)
constexpr double kSpeedBin = 0.25;             // m/s
constexpr double kAngleBin = 5.0;              // degrees
constexpr double kDentBin = 10e-6;             // m

// A fixed-bin histogram that grows its bins as values arrive (bins are few: kilobytes).
struct Histogram {
    double width;
    std::vector<std::uint64_t> bins;
    void add(double v) {
        if (!(v >= 0.0) || !std::isfinite(v)) return;
        const auto b = static_cast<std::size_t>(v / width);
        if (b >= bins.size()) bins.resize(b + 1, 0);
        ++bins[b];
    }
};

struct ComponentAnalysis {
    std::string name;
    std::unique_ptr<TriangleMesh> mesh;
    std::unique_ptr<TriangleFields> fields;
    std::unique_ptr<CoverageMap> coverage;  // empty if the material has no yield stress
    double yield_stress_pa = 0.0;
    Histogram speed{kSpeedBin, {}}, angle{kAngleBin, {}}, dent{kDentBin, {}};
    std::uint64_t impacts = 0;
    double speed_sum = 0.0, dent_sum = 0.0;
    std::vector<CoveragePoint> curve;
    std::unique_ptr<ImpactPointsVtpWriter> points;  // the impacts, for ParaView
    std::vector<Region> regions;                    // the scene's regions of the component
};

const MaterialDesc* material_named(const SceneDescription& scene, const std::string& name) {
    for (const MaterialDesc& m : scene.materials)
        if (m.name == name) return &m;
    return nullptr;
}

std::string fmt(double v, int precision = 4) {
    if (!std::isfinite(v)) return "";
    std::ostringstream s;
    s << std::setprecision(precision) << v;
    return s.str();
}

// Simulated time the log covers: from summary.json, or the scene's duration.
double simulated_time(const fs::path& dir, const SceneDescription& scene, bool& finished) {
    finished = fs::exists(dir / kImpactCsvFileName);
    std::ifstream in(dir / "summary.json");
    if (in) {
        try {
            const auto j = nlohmann::json::parse(in);
            if (j.contains("simulated_time_s")) return j["simulated_time_s"].get<double>();
        } catch (const std::exception&) {
        }
    }
    return scene.process.duration_s;
}

void write_triangle_csv(const fs::path& path, const ComponentAnalysis& c, double duration) {
    std::ostringstream s;
    s << "triangle,facet,area_mm2,impacts,impacts_per_mm2_s,mean_vn_mps,max_vn_mps,energy_J_per_m2,coverage\n";
    for (std::size_t t = 0; t < c.fields->triangle_count(); ++t) {
        s << t << ',' << (c.mesh->source_facet.empty() ? static_cast<int>(t) : c.mesh->source_facet[t]) << ','
          << fmt(c.fields->area_m2(t) * 1e6, 8) << ',' << c.fields->count(t) << ',' << fmt(c.fields->rate_per_mm2_s(t, duration), 6)
          << ',' << fmt(c.fields->mean_normal_speed(t)) << ',' << fmt(c.fields->max_normal_speed(t)) << ','
          << fmt(c.fields->energy_per_area(t), 6) << ',' << (c.coverage ? fmt(c.coverage->coverage_of_triangle(t)) : "") << '\n';
    }
    write_file_atomically(path.string(), s.str());
}

// The per-triangle fields as VTK cell data (same names and units as the CSV columns).
std::vector<CellField> cell_fields(const ComponentAnalysis& c, double duration) {
    const std::size_t n = c.fields->triangle_count();
    std::vector<CellField> f{{"impacts", 1, {}}, {"impacts_per_mm2_s", 1, {}}, {"mean_vn_mps", 1, {}},
                             {"max_vn_mps", 1, {}}, {"energy_J_per_m2", 1, {}}};
    if (c.coverage) f.push_back({"coverage", 1, {}});
    for (CellField& x : f) x.values.reserve(n);
    for (std::size_t t = 0; t < n; ++t) {
        const double mean = c.fields->mean_normal_speed(t);
        f[0].values.push_back(static_cast<double>(c.fields->count(t)));
        f[1].values.push_back(c.fields->rate_per_mm2_s(t, duration));
        f[2].values.push_back(std::isfinite(mean) ? mean : 0.0);  // ParaView: 0 where nothing hit
        f[3].values.push_back(c.fields->max_normal_speed(t));
        f[4].values.push_back(c.fields->energy_per_area(t));
        if (c.coverage) f[5].values.push_back(c.coverage->coverage_of_triangle(t));
    }
    return f;
}

void write_regions_csv(const fs::path& path, const ComponentAnalysis& c, double duration) {
    std::ostringstream s;
    s << "region,triangles,area_mm2,impacts,impacts_per_mm2_s,mean_vn_mps,max_vn_mps,energy_J_per_m2,coverage\n";
    for (const Region& region : c.regions) {
        const RegionStats r = region_stats(region, *c.fields, c.coverage.get(), duration);
        s << region.name << ',' << r.triangles << ',' << fmt(r.area_m2 * 1e6, 8) << ',' << r.impacts << ','
          << fmt(r.impacts_per_mm2_s, 6) << ',' << fmt(r.mean_normal_speed) << ',' << fmt(r.max_normal_speed) << ','
          << fmt(r.energy_per_area, 6) << ',' << fmt(r.coverage) << '\n';
    }
    write_file_atomically(path.string(), s.str());
}

// Per component with regions: one table row per region (the numbers of <component>_regions.csv).
std::string region_tables(const std::vector<ComponentAnalysis>& parts, double duration) {
    std::ostringstream r;
    for (const ComponentAnalysis& c : parts) {
        if (c.regions.empty()) continue;
        r << "\n## Regions of " << c.name << "\n\n| region | triangles | area (mm2) | impacts | per mm2 per s | mean v_n (m/s) "
             "| max v_n (m/s) | energy (J/m2) | coverage |\n|---|---|---|---|---|---|---|---|---|\n";
        for (const Region& region : c.regions) {
            const RegionStats s = region_stats(region, *c.fields, c.coverage.get(), duration);
            r << "| " << region.name << " | " << s.triangles << " | " << fmt(s.area_m2 * 1e6) << " | " << s.impacts << " | "
              << fmt(s.impacts_per_mm2_s) << " | " << fmt(s.mean_normal_speed) << " | " << fmt(s.max_normal_speed) << " | "
              << fmt(s.energy_per_area) << " | " << (c.coverage ? fmt(100.0 * s.coverage, 3) + " %" : "") << " |\n";
        }
    }
    return r.str();
}

void write_histograms_csv(const fs::path& path, const ComponentAnalysis& c) {
    std::ostringstream s;
    s << "quantity,bin_low,bin_high,unit,count\n";
    auto rows = [&](const char* q, const Histogram& h, double scale, const char* unit) {
        for (std::size_t b = 0; b < h.bins.size(); ++b)
            s << q << ',' << fmt(b * h.width * scale, 6) << ',' << fmt((b + 1) * h.width * scale, 6) << ',' << unit << ',' << h.bins[b] << '\n';
    };
    rows("normal_speed", c.speed, 1.0, "m/s");
    rows("impact_angle", c.angle, 1.0, "deg");
    rows("dent_diameter", c.dent, 1e6, "um");
    write_file_atomically(path.string(), s.str());
}

void write_curve_csv(const fs::path& path, const ComponentAnalysis& c) {
    std::ostringstream s;
    s << "time_s,coverage\n";
    for (const CoveragePoint& p : c.curve) s << fmt(p.time_s, 8) << ',' << fmt(p.coverage, 6) << '\n';
    write_file_atomically(path.string(), s.str());
}

std::string report(const fs::path& dir, const SceneDescription& scene, const std::vector<ComponentAnalysis>& parts, double duration,
                   bool finished, bool truncated, const std::vector<std::string>& pngs, const std::string& plot_note) {
    std::ostringstream r;
    r << "# peensim analysis: " << (scene.name.empty() ? dir.string() : scene.name) << "\n\n";
    r << "Run: `" << dir.string() << "`, " << fmt(duration) << " s of peening simulated"
      << (finished ? "" : " (the run did not finish: its impact log is partial)") << ".\n";
    if (truncated) r << "The impact log ended inside a row (a run killed mid-write): that row was left out.\n";
    r << "\n| component | impacts | per s | mean v_n (m/s) | mean dent (um) | coverage | Avrami k (1/s) | time to 98 % (s) |\n";
    r << "|---|---|---|---|---|---|---|---|\n";
    for (const ComponentAnalysis& c : parts) {
        const double mean_v = c.impacts ? c.speed_sum / c.impacts : NAN;
        const double mean_d = c.impacts && c.coverage ? c.dent_sum / c.impacts * 1e6 : NAN;
        std::string k = "", t98 = "", cov = "";
        if (c.coverage) {
            cov = fmt(100.0 * c.coverage->coverage(), 3) + " %";
            const AvramiFit fit = fit_avrami(c.curve);
            if (fit.points_used > 0 && fit.k_per_s > 0.0) {
                k = fmt(fit.k_per_s) + " +- " + fmt(fit.k_standard_error_per_s, 2);
                t98 = fmt(fit.time_to_98_percent_s) + (fit.extrapolated ? " (extrapolated)" : "");
            }
        } else {
            cov = "no yield_stress";
        }
        r << "| " << c.name << " | " << c.impacts << " | " << fmt(c.impacts / duration) << " | " << fmt(mean_v) << " | " << fmt(mean_d)
          << " | " << cov << " | " << k << " | " << t98 << " |\n";
    }
    r << "\nCoverage follows SAE J2277: the area fraction covered by at least one dent, each dent of diameter "
         "phi = D (8 rho v_n^2 / (9 sigma_y))^(1/4) (eq. 10), sampled on a grid of spacing a fifth of the dent at 1 m/s; "
         "98 % counts as full coverage, its time from the fit C(t) = 1 - exp(-k t).\n\nFiles (per component): "
         "`<component>_triangles.csv` (per-triangle fields), `<component>_coverage.csv` (coverage vs time), "
         "`<component>_histograms.csv` (normal speed, impact angle, dent diameter), `<component>.vtp` (the mesh with "
         "the per-triangle fields as cell data, for ParaView), `<component>_impacts.vtp` (the impacts as points with their "
         "relative velocity, normal speed and time), `<component>_regions.csv` (the scene's regions of the component, "
         "each triangle in the region holding its centroid).\n";
    r << region_tables(parts, duration);
    if (!pngs.empty()) r << "\n## Plots\n\n";
    for (const std::string& png : pngs) {
        const std::string name = fs::path(png).filename().string();
        const bool coverage = name.ends_with("_coverage.png");
        r << "![" << (coverage ? "coverage" : "histograms") << "](" << name << ")\n\n";
    }
    if (!plot_note.empty()) r << (pngs.empty() ? "\n" : "") << "Plots: " << plot_note << ".\n";
    return r.str();
}

}  // namespace

int analyze_job(const std::string& output_dir, std::ostream& out, std::ostream& err) {
    return report_errors(err, [&] {
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
        std::map<std::string, std::size_t, std::less<>> by_name;
        const double shot_mass = scene.shot.density_kg_per_m3 * M_PI / 6.0 * std::pow(scene.shot.diameter_m, 3);
        for (const ComponentDesc& c : scene.components) {
            const auto& logged = scene.output.logged_components;
            const bool is_logged = logged.empty() ? c.role == ComponentRole::part : std::find(logged.begin(), logged.end(), c.name) != logged.end();
            if (!is_logged) continue;
            ComponentAnalysis a;
            a.name = c.name;
            a.mesh = std::make_unique<TriangleMesh>(load_mesh(c.mesh_path, c.mesh_unit_m));
            a.fields = std::make_unique<TriangleFields>(*a.mesh, shot_mass);
            a.regions = select_regions(*a.mesh, c.regions);
            const MaterialDesc* m = material_named(scene, c.material);
            if (m && m->yield_stress_pa) {
                a.yield_stress_pa = *m->yield_stress_pa;
                const double area = [&] { double s = 0; for (std::size_t t = 0; t < a.mesh->triangle_count(); ++t) s += 0.5 * (a.mesh->corner(t, 1) - a.mesh->corner(t, 0)).cross(a.mesh->corner(t, 2) - a.mesh->corner(t, 0)).norm(); return s; }();
                double spacing = dent_diameter(scene.shot.diameter_m, scene.shot.density_kg_per_m3, 1.0, a.yield_stress_pa) / kDentsPerSpacing;
                spacing = std::max(spacing, std::sqrt(area / kMaxSamples));
                a.coverage = std::make_unique<CoverageMap>(*a.mesh, spacing,
                    dent_diameter(scene.shot.diameter_m, scene.shot.density_kg_per_m3, kLargestSpeed, a.yield_stress_pa));
            }
            by_name.emplace(a.name, parts.size());
            parts.push_back(std::move(a));
        }
        if (parts.empty()) throw std::runtime_error(output_dir + ": the run logged no component (output.log is empty and the scene has no part)");

        const fs::path adir = dir / "analysis";
        fs::create_directories(adir);
        for (ComponentAnalysis& a : parts)
            a.points = std::make_unique<ImpactPointsVtpWriter>((adir / (a.name + "_impacts.vtp")).string(), impact_point_field_layouts());

        ImpactLogReader reader(log.string());
        ImpactRow row;
        int next_sample = 1;
        auto sample_until = [&](double t) {
            while (next_sample <= kCoverageSamples && t >= duration * next_sample / kCoverageSamples) {
                for (ComponentAnalysis& a : parts)
                    if (a.coverage) a.curve.push_back({duration * next_sample / kCoverageSamples, a.coverage->coverage()});
                ++next_sample;
            }
        };
        for (ComponentAnalysis& a : parts)
            if (a.coverage) a.curve.push_back({0.0, 0.0});
        while (reader.next(row)) {
            sample_until(row.time_s);
            const auto it = by_name.find(row.component);
            if (it == by_name.end()) continue;
            ComponentAnalysis& a = parts[it->second];
            const double values[5] = {row.v_in_m_per_s.x(), row.v_in_m_per_s.y(), row.v_in_m_per_s.z(), row.vn_in_m_per_s, row.time_s};
            a.points->add(row.point_m, values);
            a.fields->add(row.triangle, row.point_m, row.vn_in_m_per_s);
            ++a.impacts;
            a.speed_sum += row.vn_in_m_per_s;
            a.speed.add(row.vn_in_m_per_s);
            a.angle.add(std::atan2(row.vt_in_m_per_s, row.vn_in_m_per_s) * 180.0 / M_PI);
            if (a.coverage) {
                const double d = dent_diameter(scene.shot.diameter_m, scene.shot.density_kg_per_m3, row.vn_in_m_per_s, a.yield_stress_pa);
                a.coverage->add_dent(row.point_m, d);
                a.dent.add(d);
                a.dent_sum += d;
            }
        }
        sample_until(duration);

        for (ComponentAnalysis& a : parts) {
            a.points->finish();
            write_mesh_vtp((adir / (a.name + ".vtp")).string(), *a.mesh, cell_fields(a, duration));
            write_triangle_csv(adir / (a.name + "_triangles.csv"), a, duration);
            write_histograms_csv(adir / (a.name + "_histograms.csv"), a);
            if (a.coverage) write_curve_csv(adir / (a.name + "_coverage.csv"), a);
            if (!a.regions.empty()) write_regions_csv(adir / (a.name + "_regions.csv"), a, duration);
        }
        std::vector<std::string> names;
        for (const ComponentAnalysis& a : parts) names.push_back(a.name);
        std::string plot_note;
        const std::vector<std::string> pngs = write_analysis_plots(adir.string(), names, plot_note);
        const std::string text = report(dir, scene, parts, duration, finished, reader.truncated(), pngs, plot_note);
        write_file_atomically((adir / "report.md").string(), text);
        out << text.substr(text.find("| component"), text.find("\nCoverage follows") - text.find("| component")) << "analysis: "
            << adir.string() << "/{report.md, *_triangles.csv, *_coverage.csv, *_histograms.csv, *.vtp, *_impacts.vtp"
            << (pngs.empty() ? "" : ", *.png") << "}\n";
        return 0;
    });
}

}  // namespace peensim
