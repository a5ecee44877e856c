#include "app/analysis/analyze_job.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <ostream>

#include "analysis/impact_stream.h"
#include "app/analysis/almen_analysis.h"
#include "app/analysis/analysis_figures.h"
#include "app/analysis/analysis_format.h"
#include "app/analysis/analysis_plots.h"
#include "app/analysis/analysis_report.h"
#include "app/analysis/analysis_tables.h"
#include "app/analysis/coverage_geometry.h"
#include "app/analysis/coverage_verdict.h"
#include "app/analysis/map_smoothing.h"
#include "app/analysis/report_views.h"
#include "app/checkpoint/checkpoint.h"
#include "app/component_analysis.h"
#include "app/paraview/paraview_coverage_series.h"
#include "app/paraview/paraview_script.h"
#include "app/render_module.h"
#include "app/report_errors.h"
#include "common/float_limits.h"
#include "contact/dent.h"
#include "geometry/mesh_checks.h"
#include "model/model.h"
#include "output/atomic_file.h"
#include "output/impact_csv_writer.h"
#include "output/markdown_html.h"
#include "output/run_directory.h"
#include "scene/resolved_writer.h"
#include "scene/scene_parser.h"
#include "scene/scene_sections.h"
#include "scene/shot_mix.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

constexpr int kCoverageSamples = 50;       // points of the coverage- and dose-vs-time curves
constexpr std::uint64_t kJetWindow = 500;  // impacts per window of the jet's figures

// The time of the log's last complete row (s), read from its tail; nullopt when it has no row.
// Rows come in time order (the writer logs each step's impacts after the step), so the last is
// the latest (within a step's impacts, whose times differ by less than a step).
std::optional<double> last_impact_time(const fs::path& log) {
    std::ifstream in(log, std::ios::binary | std::ios::ate);
    if (!in) return std::nullopt;
    constexpr std::streamoff kTail = 64 * 1024;  // bytes: many rows (one is ~250)
    const std::streamoff size = in.tellg();
    const std::streamoff from = std::max<std::streamoff>(0, size - kTail);
    in.seekg(from);
    std::string tail(static_cast<std::size_t>(size - from), '\0');
    in.read(tail.data(), static_cast<std::streamsize>(tail.size()));
    // The complete lines: after the first newline of the tail (unless it is the file's start) and
    // up to the last newline.
    const std::size_t end = tail.rfind('\n');
    if (end == std::string::npos) return std::nullopt;
    const std::size_t begin_of_last = tail.rfind('\n', end == 0 ? std::string::npos : end - 1);
    if (begin_of_last == std::string::npos && from > 0) return std::nullopt;  // one row longer than the tail: not a log of ours
    const std::string line = tail.substr(begin_of_last == std::string::npos ? 0 : begin_of_last + 1,
                                         end - (begin_of_last == std::string::npos ? 0 : begin_of_last + 1));
    double t = 0.0;
    const auto [ptr, ec] = std::from_chars(line.data(), line.data() + line.size(), t);
    if (ec != std::errc() || ptr == line.data() || (ptr < line.data() + line.size() && *ptr != ',') || !std::isfinite(t))
        return std::nullopt;  // the header (no row yet), or damage the reader will name
    return t;
}

// Simulated time the log covers (s). A finished run: its summary.json's (a run stopped at its
// coverage target ends before the scene's duration), else the scene's. A run that did not finish:
// the latest of what it left, its summary (interrupted: written at the stop), its checkpoint and
// its last logged impact -- a killed run has no summary, and the scene's duration would divide its
// counts by time it never simulated. Says on `err` which was used.
double simulated_time(const fs::path& dir, const SceneDescription& scene, bool& finished, std::ostream& err) {
    finished = fs::exists(dir / kImpactCsvFileName);
    std::optional<double> summary_s;
    if (std::ifstream in(dir / "summary.json"); in) {
        try {
            const auto j = nlohmann::json::parse(in);
            if (j.contains("simulated_time_s") && j["simulated_time_s"].is_number()) summary_s = j["simulated_time_s"].get<double>();
        } catch (const std::exception&) {}
    }
    if (finished) {
        if (summary_s) return *summary_s;
        // A finished run ran its duration, unless it ran until coverage and stopped at the target:
        // without its summary that end is unknown, and its last impact is the nearest bound (the
        // cap would spread its impacts over time it never simulated).
        if (!scene.process.until_coverage) return scene.process.duration_s;
        const std::optional<double> impact_s = last_impact_time(dir / kImpactCsvFileName);
        if (!impact_s) return scene.process.duration_s;
        err << "note: " << dir.string() << ": no summary.json, and the run ran until coverage: it may have stopped before its "
            << fmt(scene.process.duration_s) << " s cap; analysing to its last logged impact, at " << fmt(*impact_s) << " s\n";
        return *impact_s;
    }
    std::optional<double> checkpoint_s;
    if (fs::exists(dir / kCheckpointFileName)) {
        try {
            checkpoint_s = load_checkpoint((dir / kCheckpointFileName).string()).state.time.seconds();
        } catch (const std::exception& e) {
            err << "note: " << (dir / kCheckpointFileName).string() << " not used for the simulated time: " << e.what() << "\n";
        }
    }
    const std::optional<double> impact_s = last_impact_time(dir / kImpactCsvPartialFileName);
    double t = 0.0;
    std::string source = "nothing (no summary.json, checkpoint or logged impact)";
    const auto take = [&](const std::optional<double>& v, const std::string& what) {
        if (v && *v > t) t = *v, source = what;
    };
    take(summary_s, "its summary.json (written when it was interrupted)");
    take(checkpoint_s, "its checkpoint");
    take(impact_s, "its last logged impact");
    err << "note: " << dir.string() << ": the run did not finish; analysing the " << fmt(t) << " s it simulated (from " << source
        << (summary_s ? "" : "; no summary.json: the run was killed") << "), not the scene's " << fmt(scene.process.duration_s) << " s\n";
    if (!(t > 0.0))
        throw InputError({(dir / kImpactCsvPartialFileName).string()}, "",
                         "the run simulated no time that can be analysed: it has no impact yet");
    return t;
}

// The analysis of component ci (c its description) as the log starts streaming.
ComponentAnalysis analysis_of(CoverageGeometry& geometry, std::size_t ci, const ComponentDesc& c, const SceneDescription& scene,
                              double shot_mass, double target) {
    const Model& model = *geometry.model();
    ComponentAnalysis a;
    a.name = c.name;
    a.index = ci;
    a.role = c.role;
    a.mesh = model.components[ci].mesh;
    a.fields = std::make_unique<TriangleFields>(*a.mesh, shot_mass);
    // The geometry's (the setup check's) when it has the part, else tallied here.
    const PartCoverageGeometry* part = geometry.part(ci);
    a.regions = part != nullptr ? part->regions : RegionSet(*a.mesh, c.regions);
    a.region_tallies.assign(a.regions.size(), RegionTally{});
    a.region_histograms.assign(a.regions.size(), ImpactHistograms{});
    a.region_curves.assign(a.regions.size(), {});
    // Coverage counts only the samples a shot can reach, outside excluded regions.
    a.coverage = part_coverage(geometry, ci, target);
    if (a.coverage) {
        a.yield_stress_pa = part_yield_stress(scene, ci);
        const CoverageMap& map = a.coverage->map();
        a.reach.resize(map.triangle_count());
        for (std::size_t t = 0; t < a.reach.size(); ++t) {
            const std::int64_t n = map.samples_of_triangle(t);
            a.reach[t] = n > 0 ? static_cast<double>(a.coverage->classes().reachable_samples(t)) / static_cast<double>(n) : 0.0;
        }
        a.unreachable = part->unreachable;
    }
    const MaterialDesc* m = find_material(scene.materials, c.material);
    if (c.almen)
        a.almen =
            almen_analysis_of(c, *a.mesh, shot_mass, scene.shot.density_kg_per_m3, m && m->yield_stress_pa ? *m->yield_stress_pa : 0.0);
    // The sources that throw a jet (nozzles): their exit speeds and axes weighted by their rates.
    double rate = 0.0, v0 = 0.0;
    Vec3 axis = Vec3::Zero();
    std::size_t jets = 0;
    for (const auto& source : model.sources)
        if (const SourceOutline o = source->outline(); o.jet) {
            rate += o.rate_per_s;
            v0 += o.rate_per_s * o.jet->speed_m_per_s;
            axis += o.rate_per_s * o.jet->axis;
            ++jets;
        }
    if (rate > 0.0 && v0 > 0.0) {
        a.jet.emplace(v0 / rate, kJetWindow);
        a.jet_axis = (c.rotation.transpose() * axis).normalized();  // world -> component frame
        a.jet_normal_meaningful = jets == 1 && model.sources.size() == 1 && !c.rotation_motion;
    }
    return a;
}

// Adds one impact row (inside the window) to a component's statistics (the ParaView points are
// written by the reader thread).
void accumulate(ComponentAnalysis& a, const ImpactRow& row, const SceneDescription& scene, const AnalysisWindow& window) {
    // The impacting shot: a mix's log names its diameter, a log of one size has that size.
    const double D = row.shot_diameter_m > 0.0 ? row.shot_diameter_m : scene.shot.sizes.front().diameter_m;
    if (row.shot_diameter_m == 0.0 && scene.shot.sizes.size() > 1)
        throw std::runtime_error("the scene has a shot mix but its impact log has no shot_diameter_m column: was it written by this run?");
    const double mass = sphere_mass_kg(D, scene.shot.density_kg_per_m3);
    const double vn = row.vn_in_m_per_s;
    const double energy = 0.5 * mass * vn * vn;  // J
    const int t = a.fields->add(row.triangle, row.point_m, vn, mass);
    smooth_impact(a, row, t, mass);
    ++a.impacts;
    a.speed_sum += vn;
    const int batch =
        std::clamp(static_cast<int>((row.time_s - window.from_s) / window.length_s() * kFigureBatches), 0, kFigureBatches - 1);
    const auto b = static_cast<std::size_t>(batch);
    ++a.batch_impacts[b];
    a.batch_speed_sum[b] += vn;
    double dent = std::numeric_limits<double>::quiet_NaN();
    if (a.coverage) {
        dent = dent_diameter(D, scene.shot.density_kg_per_m3, vn, a.yield_stress_pa);
        a.coverage->add_dent(row.point_m, dent, row.time_s - window.from_s);
        a.dent_sum += dent;
        if (t >= 0) {
            // The forecast's rates: over the faces, and along the edge lines for an impact on an
            // edge of its triangle, which dents a strip along it (analysis/coverage_forecast.h).
            const auto tt = static_cast<std::size_t>(t);
            ForecastImpact f;
            for (int k = 0; k < 3; ++k) f.point_m[k] = static_cast<float>(row.point_m[k]);
            f.triangle = static_cast<std::uint32_t>(tt);
            f.dent_area_m2 = static_cast<float>(0.25 * M_PI * dent * dent);
            f.batch = static_cast<std::uint8_t>(batch);
            f.edge = static_cast<std::int8_t>(triangle_edge_at(*a.mesh, tt, row.point_m));
            a.forecast_impacts.push_back(f);
        }
    }
    a.histograms.add(vn, row.vt_in_m_per_s, dent);
    if (t >= 0 && !a.regions.empty()) {
        // Regions by the impact's own point (a triangle may straddle a boundary).
        a.regions.regions_at(row.point_m, static_cast<std::size_t>(t), a.impact_regions);
        for (std::uint32_t r : a.impact_regions) {
            a.region_tallies[r].add(vn, energy);
            a.region_histograms[r].add(vn, row.vt_in_m_per_s, dent);
        }
    }
    if (a.almen) add_almen_impact(*a.almen, t, vn, D, mass);
    if (row.shot_diameter_m > 0.0) {
        auto size = std::find_if(a.sizes.begin(), a.sizes.end(), [&](const ComponentAnalysis::SizeTally& z) { return z.diameter_m == D; });
        if (size == a.sizes.end()) size = a.sizes.insert(a.sizes.end(), ComponentAnalysis::SizeTally{D});
        ++size->impacts;
        size->speed_sum += vn;
        if (a.coverage) size->dent_sum += dent;
        size->energy_J += energy;
    }
    if (a.jet) {
        const double jet_normal =
            t >= 0 ? a.jet->v0_m_per_s() * std::abs(a.jet_axis.dot(triangle_normal(*a.mesh, static_cast<std::size_t>(t)))) : 0.0;
        a.jet->add(row.time_s, row.v_in_m_per_s.norm(), vn, jet_normal);
    }
}

// The coverage of the peened area and of every region now, as points of their curves (t: since the window opened).
void sample_coverage(ComponentAnalysis& a, double t) {
    if (!a.coverage) return;
    a.curve.push_back({t, a.coverage->coverage()});
    for (std::size_t r = 0; r < a.regions.size(); ++r) a.region_curves[r].push_back({t, a.coverage->region_coverage(r)});
}

// The watched areas the run saw reach the target after the window (seen_reached_after), as the
// forecast takes them: reached then, not forecast.
ReachedAfterWindow reached_after_window(const ComponentAnalysis& a, const AnalysisWindow& w) {
    ReachedAfterWindow later;
    later.region_s.assign(a.regions.size(), kNaN);
    for (const auto& [area, reached_at_s] : w.seen_reached_after) {
        if (area == a.name) later.whole_s = reached_at_s - w.from_s;
        for (std::size_t r = 0; r < a.regions.size(); ++r)
            if (area == a.name + "/" + a.regions.name(r)) later.region_s[r] = reached_at_s - w.from_s;
    }
    return later;
}

// Once the log is read: where coverage is heading, for the peened area, every region and everywhere.
void finish_forecast(ComponentAnalysis& a, const AnalysisWindow& window) {
    if (!a.coverage) return;
    a.forecast =
        forecast_coverage(*a.coverage, *a.mesh, a.forecast_impacts, window.length_s(), kFigureBatches, reached_after_window(a, window));
    a.forecast_impacts = {};  // done with them: the memory back before the report
    if (window.shorter_than_a_turn()) {
        // Less than a turn: the sides that have not faced the sonotrode yet have rates of no use,
        // so no time is given, only how long a run would (a turn; coverage reached stays reached).
        const auto one_turn = [&](AreaForecast& f) {
            if (f.status != AreaForecast::Status::forecast && f.status != AreaForecast::Status::never) return;
            f.status = AreaForecast::Status::too_short;
            f.run_for_s = window.turn_s;
        };
        one_turn(a.forecast.whole);
        one_turn(a.forecast.everywhere);
        for (AreaForecast& f : a.forecast.regions) one_turn(f);
    }
}

// Each part's slowest region (the last to reach the target, by the forecast) drawn highlighted
// (render module), for the report: the picture's file name per part, or a note on why there is none.
void draw_slowest_region(const Model& model, const std::vector<ComponentAnalysis>& parts, const fs::path& adir, ReportContext& context) {
    for (const ComponentAnalysis& a : parts) {
        if (!a.coverage || a.regions.empty()) continue;
        const Everywhere e = everywhere(a);
        if (e.slowest < 0) continue;
        const auto r = static_cast<std::size_t>(e.slowest);
        std::vector<double> weight(a.mesh->triangle_count(), 0.0);
        for (const RegionShare& s : a.regions.shares(r)) weight[static_cast<std::size_t>(s.triangle)] = s.fraction;
        const std::string png = a.name + "_slowest_region.png";
        const std::string title = a.name + ": the slowest region, " + a.regions.name(r) + ", now at " +
                                  fmt(100.0 * a.coverage->region_coverage(r), 3) + " % (dark: out of the shot's reach)";
        try {
            render_module().draw_region_highlight(model, a.index, weight, a.reach, a.regions.name(r), title, (adir / png).string(), 1200,
                                                  900);
            context.slowest_region_pngs.emplace_back(a.name, png);
        } catch (const std::exception& x) {
            context.picture_note = std::string("no picture of the slowest region: ") + x.what();
        }
    }
    for (const ComponentAnalysis& a : parts) {
        if (!a.coverage || !(a.unreachable.whole.area_m2 > 0.0)) continue;
        const std::string png = a.name + "_out_of_reach.png";
        const std::string title = a.name + ": " + fmt(a.unreachable.whole.area_m2 * 1e6, 4) + " mm2 out of the reach of " +
                                  fmt(a.unreachable.shot_diameter_m * 1e3, 3) + " mm shot";
        try {
            render_module().draw_region_highlight(model, a.index, a.unreachable.triangle_share, a.reach, "out of reach", title,
                                                  (adir / png).string(), 1200, 900);
            context.unreachable_pngs.emplace_back(a.name, png);
        } catch (const std::exception& x) {
            context.picture_note = std::string("no picture of the area out of reach: ") + x.what();
        }
    }
}

// The analysed window: [from, to] of the log's time, checked against it.
AnalysisWindow window_of(const AnalyzeOptions& o, double duration, const SceneDescription& scene) {
    AnalysisWindow w;
    w.from_s = o.from_s;
    w.to_s = o.to_s.value_or(duration);
    w.min_speed_m_per_s = o.min_speed_m_per_s;
    w.target_coverage = o.target_coverage.value_or(scene.process.until_coverage.value_or(kFullCoverage));
    if (!(w.from_s >= 0.0 && w.from_s < duration))
        throw InputError(
            {"--from"}, "",
            "expected a time in [0, " + fmt(duration) + ") s (the log covers " + fmt(duration) + " s), got " + fmt(w.from_s) + " s");
    if (!(w.to_s > w.from_s && w.to_s <= duration))
        throw InputError({"--to"}, "", "expected a time in (" + fmt(w.from_s) + ", " + fmt(duration) + "] s, got " + fmt(w.to_s) + " s");
    if (!(w.min_speed_m_per_s >= 0.0)) throw InputError({"--min-speed"}, "", "expected a speed >= 0 m/s");
    if (!(w.target_coverage > 0.0 && w.target_coverage <= 1.0))
        throw InputError({"--target"}, "", "expected a coverage in (0, 1] (e.g. 0.98 or 98 %)");
    w.asked_to_s = w.to_s;
    w.to_given = o.to_s.has_value();
    return w;
}

// The turn of the logged parts that rotate (the slowest, if several do): 0 when none does.
double logged_turn_s(const Model& model, const SceneDescription& scene) {
    double turn = 0.0;  // s
    for (std::size_t ci = 0; ci < scene.components.size(); ++ci) {
        const Kinematics& k = model.components[ci].kinematics;
        if (!is_logged(scene, scene.components[ci]) || k.kind != Kinematics::Kind::rotating || k.omega_rad_per_s == 0.0) continue;
        turn = std::max(turn, 2.0 * std::numbers::pi / std::abs(k.omega_rad_per_s));
    }
    return turn;
}

// Ends the window at a whole number of turns of the rotating part (unless --to says where): the
// rest of the last turn would weigh the side that faced the sonotrode in it more than the others.
void whole_turns(AnalysisWindow& w, double turn_s) {
    w.turn_s = turn_s;
    if (turn_s <= 0.0 || w.to_given || w.ends_at_target) return;
    const double turns = std::floor(w.length_s() / turn_s * (1.0 + 1e-12));
    if (turns >= 1.0) w.to_s = std::min(w.to_s, w.from_s + turns * turn_s);
}

// A folder removed, with everything in it, unless `done` is set (it was renamed into place).
struct PartialFolder {
    fs::path path;
    bool done = false;
    explicit PartialFolder(fs::path p) : path(std::move(p)) {}
    PartialFolder(const PartialFolder&) = delete;
    PartialFolder& operator=(const PartialFolder&) = delete;
    ~PartialFolder() {
        if (done) return;
        std::error_code ignored;  // nothing to do about a folder that cannot go: the next analysis clears it
        fs::remove_all(path, ignored);
    }
};

// What a run until coverage wrote of its goal in summary.json: the target and, per watched area
// ("part" or "part/region"), when it reached it (NaN: not yet).
struct RunGoal {
    double target = 0.0;
    bool reached = false;  // every watched area
    std::vector<std::pair<std::string, double>> areas;
};

std::optional<RunGoal> run_goal(const fs::path& dir) {
    std::ifstream in(dir / "summary.json");
    if (!in) return std::nullopt;
    try {
        const auto j = nlohmann::json::parse(in);
        const auto u = j.find("until_coverage");
        if (!j.value("finished", false) || u == j.end() || !u->is_object()) return std::nullopt;
        RunGoal g;
        g.target = u->value("target", 0.0);
        g.reached = u->value("reached", false);
        for (const auto& a : u->value("areas", nlohmann::json::array())) {
            const auto t = a.find("reached_at_s");
            g.areas.emplace_back(a.value("area", ""), t != a.end() && t->is_number() ? t->get<double>() : kNaN);
        }
        return g;
    } catch (const std::exception&) {
        return std::nullopt;  // an older or damaged summary: analysed as any run
    }
}

// Whether the run ended where every area of every logged part reached a target of at least
// `target` (summary.json's until_coverage, watching all of them): its end is then where the answer
// is, and cutting it back to whole turns would cut the impacts that reached it (the report would
// forecast what the run had seen).
bool ended_at_target(const std::optional<RunGoal>& goal, const SceneDescription& scene, double target) {
    if (!scene.process.until_coverage || !scene.process.until_coverage_of.empty() || !goal) return false;
    return goal->reached && target <= goal->target;
}

// The areas a run until coverage of some of them saw reach the analysis' target after the window
// was cut to whole turns: the run counted their dents to it as the analysis would over the whole
// log (the same dents on the same samples), so their times are the run's, not a forecast from
// the shorter window. Only for the whole log (a later start or a speed cut counts other dents) and
// the run's own target.
std::vector<std::pair<std::string, double>> seen_reached_after(const std::optional<RunGoal>& goal, const AnalysisWindow& w) {
    std::vector<std::pair<std::string, double>> seen;
    if (!goal || w.ends_at_target || w.to_given || w.from_s != 0.0 || w.min_speed_m_per_s != 0.0 ||
        std::abs(goal->target - w.target_coverage) > 1e-12)
        return seen;
    for (const auto& [area, reached_at_s] : goal->areas)
        if (reached_at_s > w.to_s) seen.emplace_back(area, reached_at_s);  // NaN (not reached): false
    return seen;
}

// What the report takes from the run's summary.json, when it has it.
void read_summary_figures(const fs::path& dir, ReportContext& context) {
    std::ifstream in(dir / "summary.json");
    if (!in) return;
    try {
        const auto j = nlohmann::json::parse(in);
        for (const auto& c : j.value("impacts_per_component", nlohmann::json::array()))
            if (c.value("component", "") == "shot-shot") context.shot_shot_impacts = c.value("impacts", std::uint64_t{0});
        for (const auto& e : j.value("flow_rate_eps", nlohmann::json::array()))
            context.flow_rate_eps.emplace_back(e.value("source", ""), e.value("eps", 0.0));
        context.overrides = j.value("overrides", std::vector<std::string>{});
        if (const auto r = j.find("replicas"); r != j.end() && r->is_object() && r->contains("windows")) {
            // A replica's logged time, whether one window or its slots of a run in rounds: each
            // replica started from rest once.
            std::map<int, double> logged_s;
            for (const auto& w : (*r)["windows"]) logged_s[w.value("replica", 0)] += w.value("end_s", 0.0) - w.value("start_s", 0.0);
            ReportContext::Replicas replicas;
            replicas.windows = logged_s.size();
            replicas.shortest_window_s = std::numeric_limits<double>::infinity();
            for (const auto& [replica, seconds] : logged_s) replicas.shortest_window_s = std::min(replicas.shortest_window_s, seconds);
            if (replicas.windows > 1) context.replicas = replicas;
        }
        const double wall = j.value("wall_time_s", 0.0), simulated = j.value("simulated_time_s", 0.0);
        if (wall > 0.0 && simulated > 0.0) context.wall_per_simulated_s = wall / simulated;
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
    bool finished = fs::exists(dir / kImpactCsvFileName);
    const fs::path log = finished ? dir / kImpactCsvFileName : dir / kImpactCsvPartialFileName;
    if (!fs::exists(log)) throw std::runtime_error(output_dir + ": no impact log (impacts.csv or impacts.csv.partial)");
    const double duration = simulated_time(dir, scene, finished, err);
    AnalysisWindow window = window_of(options, duration, scene);

    // The model: the logged components' meshes, and which of their facets the shot can reach.
    // The run's own, with the coverage geometry it computed while it stepped, when it is of this
    // scene; else compiled afresh, the geometry computed here.
    const bool own_model = options.model && options.model->resolved_scene_yaml == resolved_scene_yaml(scene);
    const std::shared_ptr<const Model> model = own_model ? options.model : compile_model(scene);
    std::shared_ptr<CoverageGeometry> geometry =
        own_model && options.geometry && options.geometry->model() == model
            ? options.geometry
            : std::make_shared<CoverageGeometry>(model, nullptr, 0, std::vector<std::optional<RegionSet>>{}, options.geometry_cache_dir);
    // The run's coverage is its whole log's: a window that starts later or leaves out slow impacts
    // counts less of it, and its forecasts read whole turns.
    const std::optional<RunGoal> goal = finished ? run_goal(dir) : std::nullopt;
    window.ends_at_target =
        !window.to_given && window.from_s == 0.0 && window.min_speed_m_per_s == 0.0 && ended_at_target(goal, scene, window.target_coverage);
    whole_turns(window, logged_turn_s(*model, scene));
    window.seen_reached_after = seen_reached_after(goal, window);
    std::vector<ComponentAnalysis> parts;
    std::vector<std::string> names;
    const double shot_mass = mean_shot_mass_kg(scene.shot);  // each impact brings its own (accumulate)
    for (std::size_t ci = 0; ci < scene.components.size(); ++ci) {
        const ComponentDesc& c = scene.components[ci];
        if (!is_logged(scene, c)) continue;
        parts.push_back(analysis_of(*geometry, ci, c, scene, shot_mass, window.target_coverage));
        start_smoothing(parts.back(), scene, c, dir, options.smoothing_radius, std::min(1.0, window.length_s() / duration));
        names.push_back(c.name);
    }
    if (parts.empty())
        throw std::runtime_error(output_dir + ": the run logged no component (output.log is empty and the scene has no part)");

    const fs::path adir = dir / kAnalysisPartialDirName;  // analysis/ once complete (run_directory.h)
    fs::remove_all(adir);
    fs::create_directories(adir);
    // An analysis that fails (a full disk, a damaged log) leaves no half of itself behind; the
    // threads and writers that use the folder are declared after this and end before it goes.
    PartialFolder partial{adir};
    for (ComponentAnalysis& a : parts)
        a.points = std::make_unique<ImpactPointsVtpWriter>((adir / (a.name + "_impacts.vtp")).string(), impact_point_field_layouts());

    // An impact is analysed when it lies in the window and is fast enough.
    const auto taken = [&window](const ImpactRow& row) {
        return row.time_s >= window.from_s && row.time_s <= window.to_s && row.vn_in_m_per_s >= window.min_speed_m_per_s;
    };
    int next_sample = 1;
    auto sample_until = [&](double t) {
        // The last sample is the window's end exactly (from + length may round past it).
        const auto sample_time = [&](int k) {
            return k == kCoverageSamples ? window.to_s : window.from_s + window.length_s() * k / kCoverageSamples;
        };
        while (next_sample <= kCoverageSamples && t >= sample_time(next_sample)) {
            const double since = sample_time(next_sample) - window.from_s;  // s since the window opened
            for (ComponentAnalysis& a : parts) {
                sample_coverage(a, since);
                if (a.almen) sample_almen(*a.almen, since);
            }
            ++next_sample;
        }
    };
    CoverageSeries coverage_series(adir, parts, window, scene.output.coverage_steps);  // for ParaView
    for (ComponentAnalysis& a : parts) {
        sample_coverage(a, 0.0);
        if (a.almen) sample_almen(*a.almen, 0.0);
    }
    // The reader thread parses the log and writes the ParaView points; this one does the rest.
    // Every logged component is named: a row of another is damage, refused with its line.
    ImpactStream stream(
        log.string(), names,
        [&parts, &taken](const ImpactRow& row, int component) {
            if (!taken(row)) return;
            const double values[5] = {row.v_in_m_per_s.x(), row.v_in_m_per_s.y(), row.v_in_m_per_s.z(), row.vn_in_m_per_s, row.time_s};
            parts[static_cast<std::size_t>(component)].points->add(row.point_m, values);
        },
        true);
    for (auto block = stream.next_block(); !block.empty(); block = stream.next_block()) {
        for (const IndexedImpact& impact : block) {
            if (!taken(impact.row)) continue;
            sample_until(impact.row.time_s);
            coverage_series.before(impact.row.time_s);
            if (impact.component >= 0) accumulate(parts[static_cast<std::size_t>(impact.component)], impact.row, scene, window);
        }
    }
    sample_until(window.to_s);
    coverage_series.finish();
    if (stream.truncated())
        err << "warning: " << log.string() << ":" << stream.truncated_line() << ": the impact log ends inside row " << stream.rows() + 1
            << " (line " << stream.truncated_line() << "): the log was cut"
            << (finished ? " after the run finished (a finished run's log ends with a whole row: copied in part?)"
                         : " (a run killed while writing it)")
            << "; that row is left out, the " << stream.rows() << " rows before it are analysed\n";

    for (ComponentAnalysis& a : parts) {
        a.points->finish();
        // The smoothed maps and their per-triangle files need nothing of the forecast: they are
        // made beside it, on the core its serial steps leave idle (all of them only read the
        // coverage; the forecast writes only its own members).
        auto maps = std::async(std::launch::async, [&a, &adir, &window] {
            finish_smoothing(a);
            write_triangle_tables(adir, a, window);
        });
        try {
            finish_forecast(a, window);
        } catch (...) {
            maps.wait();  // it reads a: done before the error leaves
            throw;
        }
        maps.get();
        write_component_tables(adir, a, window);
    }
    ReportContext context;
    context.run_dir = dir;
    context.window = window;
    context.log_duration_s = duration;
    context.finished = finished;
    context.truncated = stream.truncated();
    read_summary_figures(dir, context);
    context.watches_some_areas = !scene.process.until_coverage_of.empty();
    // The plots (gnuplot's processes) and the report's 3D views (a thinned mesh per part: ~0.5 s of
    // one core on a 500k-triangle part) are made while the render module draws the slowest
    // regions. Each writes its own members of the context.
    std::string plot_note;
    auto plots =
        std::async(std::launch::async, [&] { return write_analysis_plots(adir.string(), names, window.target_coverage, plot_note); });
    auto made_views = std::async(std::launch::async, [&] { return report_views(parts, window, three_js_library_dir(), context); });
    draw_slowest_region(*model, parts, adir, context);
    context.pngs = plots.get();
    context.plot_note = plot_note;
    const std::map<std::string, std::string> views = made_views.get();
    if (!context.view_note.empty()) out << "analysis: " << context.view_note << "\n";
    // Also in the report; said even to a quiet run (a sweep's log), as pictures asked for are missing.
    if (!context.picture_note.empty()) err << "warning: " << context.picture_note << "\n";
    const std::string report = analysis_report(scene, parts, context);
    write_file_atomically((adir / "report.md").string(), report);
    // The same page with its pictures inside: one file to send.
    write_file_atomically((adir / "report.html").string(),
                          markdown_to_html(report, "peensim analysis: " + (scene.name.empty() ? output_dir : scene.name),
                                           image_files_in(adir.string()), views));
    write_file_atomically((adir / "figures.json").string(), analysis_figures_json(parts, window));
    write_paraview_script(dir, adir, scene, fastest_start_speed_m_per_s(model->sources), parts, duration, window);
    coverage_series.wait();
    const fs::path done = dir / kAnalysisDirName;
    fs::remove_all(done);
    fs::rename(adir, done);
    partial.done = true;
    out << analysis_summary_table(parts, window) << "analysis: " << done.string()
        << "/{report.md, report.html, *_triangles.csv, *_coverage.csv, *_histograms.csv, *.vtp, *_impacts.vtp, *_coverage_series.pvd"
        << (context.pngs.empty() ? "" : ", *.png") << ", " << kParaviewScriptFileName << "}\n";
    for (const ComponentAnalysis& a : parts) out << smoothing_note(a) << '\n';
    // On the messages' stream: a sweep's runs are quiet, and their logs say which computed it.
    for (const ComponentAnalysis& a : parts)
        if (const PartCoverageGeometry* part = geometry->part(a.index); part != nullptr && !part->cache_note.empty())
            err << "note: " << a.name << "'s coverage geometry " << part->cache_note << '\n';
}

}  // namespace peensim
