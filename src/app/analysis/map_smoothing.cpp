#include "app/analysis/map_smoothing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <vector>

#include "analysis/impact_log_reader.h"
#include "app/component_analysis.h"
#include "common/input_error.h"
#include "common/units.h"
#include "contact/dent.h"
#include "scene/shot_mix.h"

namespace peensim {

namespace {

// The component's mean normal speed (m/s) and impact count from the run's summary.json.
struct SummaryFigures {
    std::optional<double> mean_normal_speed_m_per_s;
    std::uint64_t impacts = 0;
};
SummaryFigures summary_figures(const std::filesystem::path& run_dir, const std::string& component) {
    SummaryFigures f;
    std::ifstream in(run_dir / "summary.json");
    if (!in) return f;
    try {
        const auto j = nlohmann::json::parse(in);
        for (const auto& n : j.value("normal_speed", nlohmann::json::array()))
            if (n.value("component", "") == component) {
                f.impacts = n.value("count", std::uint64_t{0});
                const double mean = n.value("mean_normal_speed_mps", 0.0);
                if (f.impacts > 0 && mean > 0.0) f.mean_normal_speed_m_per_s = mean;
            }
    } catch (const std::exception&) {}  // an older or damaged summary: the fallbacks
    return f;
}

std::string millimetres(double metres) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g mm", metres * 1e3);
    return text;
}

}  // namespace

std::optional<double> smoothing_radius_option(const std::string& text) {
    if (text.empty()) return std::nullopt;
    double radius = 0.0;
    try {
        radius = parse_quantity(text, Dimension::length);
    } catch (const QuantityError& e) {
        throw InputError({"--smoothing-radius"}, "", e.what());
    }
    if (!(radius >= 1e-6 && radius <= 1.0))
        throw InputError({"--smoothing-radius"}, "", "expected a length from 1 um to 1 m, got '" + text + "'");
    return radius;
}

SmoothingChoice choose_smoothing_radius(const SceneDescription& scene, const ComponentDesc& component, const std::filesystem::path& run_dir,
                                        double area_m2, std::optional<double> command_line_radius_m, double window_share) {
    if (command_line_radius_m) return {*command_line_radius_m, "set by --smoothing-radius"};
    if (scene.output.smoothing_radius_m) return {*scene.output.smoothing_radius_m, "set by output.smoothing_radius"};
    const SummaryFigures figures = summary_figures(run_dir, component.name);
    // The dent scale.
    const MaterialDesc* material = nullptr;
    for (const MaterialDesc& m : scene.materials)
        if (m.name == component.material) material = &m;
    SmoothingChoice choice{kFallbackSmoothingRadius, ""};
    char text[192];
    if (material == nullptr || !material->yield_stress_pa) {
        choice.basis = "1 mm: no dent size, the material has no yield_stress";
    } else if (!figures.mean_normal_speed_m_per_s) {
        choice.basis = "1 mm: no dent size, summary.json has no mean normal speed";
    } else {
        const std::vector<double> shares = count_fractions(scene.shot);
        double diameter = 0.0;  // m, the mix's mean by count
        for (std::size_t k = 0; k < shares.size(); ++k) diameter += shares[k] * scene.shot.sizes[k].diameter_m;
        const double dent =
            dent_diameter(diameter, scene.shot.density_kg_per_m3, *figures.mean_normal_speed_m_per_s, *material->yield_stress_pa);
        choice.radius_m = kSmoothingDents * dent;
        std::snprintf(text, sizeof text, "%g dents of %s at the mean normal speed %.3g m/s (eq. 10)", kSmoothingDents,
                      millimetres(dent).c_str(), *figures.mean_normal_speed_m_per_s);
        choice.basis = text;
    }
    // The noise scale: lambda 5 pi R^2 / 9 = kKernelImpacts at the mean density lambda.
    if (figures.impacts > 0 && area_m2 > 0.0 && window_share > 0.0) {
        const double density = static_cast<double>(figures.impacts) * window_share / area_m2;  // impacts per m2
        const double noise_radius = std::sqrt(kKernelImpacts * 9.0 / (5.0 * std::numbers::pi * density));
        if (noise_radius > choice.radius_m) {
            std::snprintf(text, sizeof text, "; widened from %s to hold %g impacts at the mean density (+-%.0f %%)",
                          millimetres(choice.radius_m).c_str(), kKernelImpacts, 100.0 / std::sqrt(kKernelImpacts));
            choice.basis += text;
            choice.radius_m = noise_radius;
        }
    }
    return choice;
}

void start_smoothing(ComponentAnalysis& a, const SceneDescription& scene, const ComponentDesc& component,
                     const std::filesystem::path& run_dir, const std::string& option_text, double window_share) {
    double area = 0.0;  // m2
    for (std::size_t t = 0; t < a.fields->triangle_count(); ++t) area += a.fields->area_m2(t);
    const SmoothingChoice choice =
        choose_smoothing_radius(scene, component, run_dir, area, smoothing_radius_option(option_text), window_share);
    a.smoothing = std::make_unique<SurfaceSmoothing>(*a.mesh, choice.radius_m);
    a.smoothing_basis = choice.basis;
}

void smooth_impact(ComponentAnalysis& a, const ImpactRow& row, int t, double mass_kg) {
    if (t < 0 || !a.smoothing) return;
    const double vn = row.vn_in_m_per_s;
    a.smoothing->add_impact(row.point_m, static_cast<std::size_t>(t), vn, 0.5 * mass_kg * vn * vn);
}

void finish_smoothing(ComponentAnalysis& a) {
    if (!a.smoothing) return;
    if (a.coverage) a.smoothing->add_coverage(a.coverage->map());
    a.smoothed = a.smoothing->at_triangles();
}

std::string smoothing_note(const ComponentAnalysis& a) {
    if (!a.smoothing) return "";
    // The median over the surface's area of the relative standard error (where impacts landed).
    std::vector<std::pair<double, double>> errors;  // (relative error, area m2)
    double total = 0.0;
    for (std::size_t t = 0; t < a.smoothed.size(); ++t) {
        const double e = a.smoothed[t].relative_error();
        if (!std::isfinite(e)) continue;
        errors.emplace_back(e, a.fields->area_m2(t));
        total += a.fields->area_m2(t);
    }
    std::sort(errors.begin(), errors.end());
    double median = std::numeric_limits<double>::quiet_NaN(), covered = 0.0;
    for (const auto& [e, area] : errors)
        if ((covered += area) >= 0.5 * total) {
            median = e;
            break;
        }
    char line[256];
    std::snprintf(line, sizeof line, "%s: maps smoothed over %s (%s)", a.name.c_str(), millimetres(a.smoothing->radius_m()).c_str(),
                  a.smoothing_basis.c_str());
    std::string note = line;
    if (std::isfinite(median)) {
        std::snprintf(line, sizeof line, "; impact density +-%.0f %% (median standard error where hit)", 100.0 * median);
        note += line;
    }
    const double cell = a.smoothing->cell_m();
    if (cell > 1.01 * a.smoothing->radius_m() / kSmoothingCellsPerRadius) {
        std::snprintf(line, sizeof line, "; binned in %s cubes, coarser than a quarter radius (a large part: at most %zu patches)",
                      millimetres(cell).c_str(), kMaxSmoothingPatches);
        note += line;
    }
    if (a.smoothing->unplaced_impacts() > 0)
        note += "; " + std::to_string(a.smoothing->unplaced_impacts()) + " impacts off the surface left out";
    return note;
}

}  // namespace peensim
