#include "app/sweep/sweep_views.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "app/analysis/report_views.h"
#include "common/csv_column.h"
#include "geometry/vertex_clustering.h"
#include "model/model.h"
#include "scene/scene_parser.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// The per-triangle columns a variant's view averages over its runs, and how the view shows them.
struct Column {
    const char* csv;
    double scale;
};
constexpr Column kColumns[] = {{"coverage", 100.0}, {"impacts_per_mm2_s_smoothed", 1.0}, {"mean_vn_mps_smoothed", 1.0}, {"peened", 1.0}};

}  // namespace

std::map<std::string, std::string> sweep_views(const SweepPlan& plan, const std::string& component, double target,
                                               const std::string& library_dir, std::string& note) {
    std::map<std::string, std::string> blocks;
    const std::optional<std::string> scripts = view_scripts(library_dir);
    if (!scripts) {
        note = no_view_library_note(library_dir);
        return blocks;
    }
    // The analysed runs of each variant.
    std::vector<std::vector<fs::path>> tables(plan.variants.size());
    std::size_t shown_variants = 0;
    for (const SweepRun& run : plan.runs) {
        const fs::path csv = fs::path(run.dir) / "analysis" / (component + "_triangles.csv");
        if (fs::exists(csv) && fs::exists(fs::path(run.dir) / "scene.resolved.yaml")) tables[run.variant].push_back(csv);
    }
    for (const auto& t : tables) shown_variants += t.empty() ? 0 : 1;
    if (shown_variants == 0) {
        note = "No 3D view: no run of the sweep has been analysed.";
        return blocks;
    }
    const std::size_t per_variant = std::max<std::size_t>(1000, kViewMaxTriangles / shown_variants);

    PartView v;
    v.name = component;
    constexpr float kNone = std::numeric_limits<float>::quiet_NaN();
    std::vector<std::vector<float>> values(std::size(kColumns) + 1);  // the columns (the last only read), then the region
    double x_mm = 0.0;                                                // mm, where the next variant's left end goes
    std::vector<std::string> skipped;
    for (std::size_t k = 0; k < plan.variants.size(); ++k) {
        if (tables[k].empty()) {
            skipped.push_back(plan.variants[k].name);
            continue;
        }
        const auto model =
            compile_model(parse_scene_file((tables[k].front().parent_path().parent_path() / "scene.resolved.yaml").string()));
        const int index = model->component_index(component);
        if (index < 0) {
            skipped.push_back(plan.variants[k].name);
            continue;
        }
        const TriangleMesh& mesh = *model->components[static_cast<std::size_t>(index)].mesh;
        // Each column's mean over the runs whose table fits the mesh.
        std::vector<std::vector<double>> sums(std::size(kColumns), std::vector<double>(mesh.triangle_count(), 0.0));
        std::vector<std::vector<int>> counts(std::size(kColumns), std::vector<int>(mesh.triangle_count(), 0));
        std::vector<std::string> region;
        for (const fs::path& csv : tables[k]) {
            std::vector<std::vector<double>> columns;
            for (const Column& c : kColumns) columns.push_back(read_csv_numbers(csv, c.csv));
            if (columns.front().size() != mesh.triangle_count()) continue;
            for (std::size_t c = 0; c < columns.size(); ++c)
                for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
                    if (std::isfinite(columns[c][t])) sums[c][t] += columns[c][t] * kColumns[c].scale, ++counts[c][t];
            if (region.empty()) region = read_csv_texts(csv, "region");
        }
        const ThinnedMesh shown = thin_for_display(mesh, per_variant);
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;  // mm, its x extent
        for (const Vec3& p : shown.vertices) lo = std::min(lo, p.x() * 1e3), hi = std::max(hi, p.x() * 1e3);
        const auto base = static_cast<std::uint32_t>(v.positions_mm.size() / 3);
        for (const Vec3& p : shown.vertices) {
            v.positions_mm.push_back(static_cast<float>(p.x() * 1e3 - lo + x_mm));
            v.positions_mm.push_back(static_cast<float>(p.y() * 1e3));
            v.positions_mm.push_back(static_cast<float>(p.z() * 1e3));
        }
        v.offsets_mm.push_back(static_cast<float>(x_mm - lo));
        x_mm += 1.25 * std::max(hi - lo, 1.0);
        const auto copy = static_cast<std::uint32_t>(v.instances.size());
        v.instances.push_back(plan.variants[k].name);
        for (std::size_t s = 0; s < shown.triangles.size(); ++s) {
            for (int corner : shown.triangles[s]) v.indices.push_back(base + static_cast<std::uint32_t>(corner));
            const std::uint32_t t = shown.source[s];
            v.source.push_back(t);
            v.instance.push_back(copy);
            for (std::size_t c = 0; c < std::size(kColumns); ++c)
                values[c].push_back(counts[c][t] > 0 ? static_cast<float>(sums[c][t] / counts[c][t]) : kNone);
            // Coverage only where it counts (the "peened" share): an excluded bore is not an unpeened one.
            if (!(values[3].back() > 0.0f)) values[0].back() = kNone;
            values[3].pop_back();
            float r = -1.0f;
            if (t < region.size() && !region[t].empty()) {
                auto it = std::find_if(v.regions.begin(), v.regions.end(), [&](const PartViewRegion& x) { return x.name == region[t]; });
                if (it == v.regions.end()) it = v.regions.insert(v.regions.end(), PartViewRegion{region[t], ""});
                r = static_cast<float>(it - v.regions.begin());
            }
            values.back().push_back(r);
        }
    }
    v.fields.push_back({"coverage", "coverage (%)", "%", std::move(values[0]), 0.0, 100.0, 100.0 * target, 1, false, false,
                        "not counted (out of the shot's reach, or excluded)"});
    PartViewField density{"impacts_per_mm2_s_smoothed",
                          "impact density (impacts/mm2/s, smoothed)",
                          "/mm2/s",
                          std::move(values[1]),
                          0.0,
                          1.0,
                          std::nullopt,
                          4,
                          false,
                          false,
                          ""};
    PartViewField speed{"mean_vn_mps_smoothed",
                        "mean normal speed (m/s, smoothed)",
                        "m/s",
                        std::move(values[2]),
                        0.0,
                        1.0,
                        std::nullopt,
                        3,
                        false,
                        false,
                        "no impact within the smoothing radius"};
    // One colour bar for all the variants: their values together.
    if (set_colour_range(density, true)) v.fields.push_back(std::move(density));
    if (set_colour_range(speed, true)) v.fields.push_back(std::move(speed));
    if (!v.regions.empty())
        v.fields.push_back({"region", "region", "", std::move(values[4]), 0.0, 1.0, std::nullopt, 0, true, false, "in no region"});
    // Far below the target the coverage is one colour: draw the impact density first.
    double covered = 0.0;
    std::size_t finite = 0;
    for (float x : v.fields[0].values)
        if (std::isfinite(x)) covered += x, ++finite;
    if (finite > 0 && covered / static_cast<double>(finite) < 50.0 * target)
        for (std::size_t k = 0; k < v.fields.size(); ++k)
            if (v.fields[k].name == "impacts_per_mm2_s_smoothed") v.shown = k;
    std::string names;
    for (const std::string& n : v.instances) names += (names.empty() ? "" : ", ") + n;
    v.note = "Left to right: " + names + ". Per triangle the mean over each variant's analysed runs (seeds)" +
             (per_variant < kViewMaxTriangles ? "; a part of more than " + std::to_string(per_variant) + " triangles is thinned for display"
                                              : std::string()) +
             "." + (skipped.empty() ? std::string() : " Not shown (no analysed run): " + std::to_string(skipped.size()) + " variant(s).");
    blocks[kSweepViewMarker] = *scripts + part_view_html(v);
    return blocks;
}

}  // namespace peensim
