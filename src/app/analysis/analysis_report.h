// report.md of `peensim analyze`: the numbers and plots of every logged component on one page.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/component_analysis.h"
#include "scene/scene_description.h"

namespace peensim {

struct ReportContext {
    std::filesystem::path run_dir;
    AnalysisWindow window;          // what of the log was analysed
    double log_duration_s = 0.0;    // s, simulated time the log covers
    bool finished = true;           // false: the run was interrupted (partial log)
    bool truncated = false;         // the log ended inside a row
    std::vector<std::string> pngs;  // plots written (paths)
    std::string plot_note;          // why plots are missing, or ""
    // Per logged component (by name): the picture of its slowest region, or why there is none.
    std::vector<std::pair<std::string, std::string>> slowest_region_pngs;
    std::vector<std::pair<std::string, std::string>> unreachable_pngs;  // the area out of the shot's reach
    std::string picture_note;
    // From the run's summary.json, when it has them: shot-shot collisions, each nozzle's eps, and
    // the run's wall time per simulated second (what a longer run will cost).
    std::optional<std::uint64_t> shot_shot_impacts;
    std::vector<std::pair<std::string, double>> flow_rate_eps;
    std::optional<double> wall_per_simulated_s;
    std::vector<std::string> overrides;  // the run's --set options (summary.json): the title says them
    bool watches_some_areas = false;     // the scene's process.until_coverage_of names areas (a run until every region clears it)
    // A run as replicas (`--replicas K`, summary.json): each window follows a start from rest.
    struct Replicas {
        std::size_t windows = 0;
        double shortest_window_s = 0.0;  // s
    };
    std::optional<Replicas> replicas;
    // The parts report.html shows in 3D (report_views.h), or why it shows none.
    std::vector<std::string> views;
    std::string view_note;
};

// A forecast in a table cell: "1320 s [1279-1383 s]", "reached at 41 s", "too short to say (run 40 s)".
std::string forecast_cell(const AreaForecast& f);

// The line of report.md that report.html replaces by the 3D view of `part` (an HTML comment:
// Markdown viewers show nothing).
inline std::string part_view_marker(const std::string& part) { return "<!-- 3D view: " + part + " -->"; }

std::string analysis_report(const SceneDescription& scene, const std::vector<ComponentAnalysis>& parts, const ReportContext& context);

// The summary table of the report (what `peensim run` and `analyze` print on the terminal).
std::string analysis_summary_table(const std::vector<ComponentAnalysis>& parts, const AnalysisWindow& window);

}  // namespace peensim
