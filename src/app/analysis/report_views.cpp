#include "app/analysis/report_views.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>

#include "app/analysis/analysis_format.h"
#include "geometry/vertex_clustering.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

constexpr float kNone = std::numeric_limits<float>::quiet_NaN();

std::optional<std::string> read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// Whether a part gets a view: a mesh, and coverage or smoothed maps (a material without a yield
// stress has no coverage, but its impacts still have a density and a speed).
bool shows(const ComponentAnalysis& c) { return c.mesh && c.mesh->triangle_count() > 0 && (c.coverage || !c.smoothed.empty()); }

}  // namespace

std::optional<std::string> view_scripts(const std::string& library_dir) {
    const fs::path dir(library_dir);
    const std::optional<std::string> three = read_text(dir / "three.min.js");
    const std::optional<std::string> orbit = read_text(dir / "examples/js/controls/OrbitControls.js");
    if (!three || !orbit) return std::nullopt;
    return part_view_scripts(*three, *orbit);
}

std::string no_view_library_note(const std::string& library_dir) {
    return "No 3D view in report.html: it inlines three.js from Debian's libjs-three, not found in " + library_dir +
           " (`apt-get install libjs-three`, or set PEENSIM_THREE_JS to a folder holding three.min.js and "
           "examples/js/controls/OrbitControls.js; then `peensim analyze` the run, or the sweep's command, again).";
}

PartView part_view_of(const ComponentAnalysis& c, const AnalysisWindow& window) {
    PartView v;
    v.name = c.name;
    const ThinnedMesh shown = thin_for_display(*c.mesh, kViewMaxTriangles);
    v.positions_mm.reserve(3 * shown.vertices.size());
    for (const Vec3& p : shown.vertices)
        for (int k = 0; k < 3; ++k) v.positions_mm.push_back(static_cast<float>(p[k] * 1e3));
    for (const auto& t : shown.triangles)
        for (int k : t) v.indices.push_back(static_cast<std::uint32_t>(k));
    v.source = shown.source;
    if (shown.cell_m > 0.0)
        v.note = "Shown: " + std::to_string(shown.triangles.size()) + " of the part's " + std::to_string(c.mesh->triangle_count()) +
                 " triangles (vertices merged in cubes of " + fmt(shown.cell_m * 1e3, 3) +
                 " mm for display); a click reads the values of the part's triangle it falls on.";

    const double duration = window.length_s();  // s
    const auto per_shown = [&](auto&& value_of) {
        std::vector<float> values;
        values.reserve(v.source.size());
        for (std::uint32_t t : v.source) {
            const double x = value_of(static_cast<std::size_t>(t));
            values.push_back(std::isfinite(x) ? static_cast<float>(x) : kNone);
        }
        return values;
    };
    // A field is offered when it has a value somewhere; the coverage bars run 0-100 % with the
    // target marked, the others over their values (the region's time from the earliest).
    const auto add = [&v](PartViewField f, bool fixed_range, bool from_zero) {
        if (fixed_range ? std::none_of(f.values.begin(), f.values.end(), [](float x) { return std::isfinite(x); })
                        : !set_colour_range(f, from_zero))
            return;
        v.fields.push_back(std::move(f));
    };
    const std::optional<double> target = 100.0 * window.target_coverage;
    const std::string not_counted = "not counted (out of the shot's reach, or excluded)";
    if (c.coverage) {
        // Only where coverage counts: an excluded bore is not an unpeened one.
        const auto counted = [&](std::size_t t) { return c.coverage->peened_share(t) > 0.0; };
        add({"coverage", "coverage (%)", "%",
             per_shown([&](std::size_t t) { return counted(t) ? 100.0 * c.coverage->shown_triangle_coverage(t) : std::nan(""); }), 0.0,
             100.0, target, 1, false, false, not_counted},
            true, true);
        if (!c.smoothed.empty())
            add({"coverage_smoothed", "coverage (%, smoothed)", "%",
                 per_shown([&](std::size_t t) { return counted(t) ? 100.0 * c.smoothed[t].coverage() : std::nan(""); }), 0.0, 100.0, target,
                 1, false, false, not_counted},
                true, true);
    }
    if (!c.smoothed.empty()) {
        add({"impacts_per_mm2_s_smoothed", "impact density (impacts/mm2/s, smoothed)", "/mm2/s",
             per_shown([&](std::size_t t) { return c.smoothed[t].impacts_per_m2() / 1e6 / duration; }), 0.0, 1.0, std::nullopt, 4, false,
             false, ""},
            false, true);
        add({"mean_vn_mps_smoothed", "mean normal speed (m/s, smoothed)", "m/s",
             per_shown([&](std::size_t t) { return c.smoothed[t].mean_normal_speed(); }), 0.0, 1.0, std::nullopt, 3, false, false,
             "no impact within the smoothing radius"},
            false, true);
    }
    if (!c.regions.empty()) {
        for (std::size_t r = 0; r < c.regions.size(); ++r)
            v.regions.push_back(
                {c.regions.name(r), c.coverage && r < c.forecast.regions.size() ? forecast_cell(c.forecast.regions[r]) : ""});
        const auto region_time = [&](std::size_t t) {
            const int r = c.regions.dominant_region(t);
            if (r < 0 || !c.coverage || static_cast<std::size_t>(r) >= c.forecast.regions.size()) return std::nan("");
            const AreaForecast& f = c.forecast.regions[static_cast<std::size_t>(r)];
            const bool timed = f.status == AreaForecast::Status::forecast || f.status == AreaForecast::Status::reached;
            return timed ? f.time_s : std::nan("");
        };
        add({"region_time_to_target_s", "time to the target of its region (s, forecast)", "s", per_shown(region_time), 0.0, 1.0,
             std::nullopt, 0, false, false, "no forecast for its region (too short to say, excluded, or no region)"},
            false, false);
        v.fields.push_back({"region", "region", "",
                            per_shown([&](std::size_t t) { return static_cast<double>(c.regions.dominant_region(t)); }), 0.0, 1.0,
                            std::nullopt, 0, true, false, "in no region"});
    }
    // Far below the target the coverage field is one colour (a 5 s run of a part that needs 20
    // minutes): draw where the impacts land first, the coverage one choice away.
    const bool low = c.coverage && c.coverage->coverage() < 0.5 * window.target_coverage;
    for (std::size_t k = 0; k < v.fields.size(); ++k)
        if ((low || !c.coverage) && v.fields[k].name == "impacts_per_mm2_s_smoothed") v.shown = k;
    return v;
}

std::map<std::string, std::string> report_views(const std::vector<ComponentAnalysis>& parts, const AnalysisWindow& window,
                                                const std::string& library_dir, ReportContext& context) {
    std::map<std::string, std::string> blocks;
    bool any = false;
    for (const ComponentAnalysis& c : parts) any = any || shows(c);
    if (!any) return blocks;
    const std::optional<std::string> scripts = view_scripts(library_dir);
    if (!scripts) {
        context.view_note = no_view_library_note(library_dir);
        return blocks;
    }
    for (const ComponentAnalysis& c : parts) {
        if (!shows(c)) continue;
        std::string html = blocks.empty() ? *scripts : std::string();
        html += part_view_html(part_view_of(c, window));
        blocks[part_view_marker(c.name)] = std::move(html);
        context.views.push_back(c.name);
    }
    return blocks;
}

}  // namespace peensim
