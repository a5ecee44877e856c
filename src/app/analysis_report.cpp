#include "app/analysis_report.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "analysis/region_stats.h"
#include "app/almen_analysis.h"
#include "app/analysis_format.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// Per component with regions: one table row per region (the numbers of <component>_regions.csv).
std::string region_tables(const std::vector<ComponentAnalysis>& parts, double duration) {
    std::ostringstream r;
    for (const ComponentAnalysis& c : parts) {
        if (c.regions.empty()) continue;
        r << "\n## Regions of " << c.name
          << "\n\n| region | triangles | area (mm2) | impacts | per mm2 per s | mean v_n (m/s) "
             "| max v_n (m/s) | energy (J/m2) | coverage |\n|---|---|---|---|---|---|---|---|---|\n";
        for (const Region& region : c.regions) {
            const RegionStats s = region_stats(region, *c.fields, c.coverage.get(), duration);
            r << "| " << region.name << " | " << s.triangles << " | " << fmt(s.area_m2 * 1e6) << " | " << s.impacts << " | "
              << fmt(s.impacts_per_mm2_s) << " | " << fmt(s.mean_normal_speed) << " | " << fmt(s.max_normal_speed) << " | "
              << fmt(s.energy_per_area) << " | " << (c.coverage ? fmt(100.0 * s.coverage, 3) + " %" : "") << " |\n";
        }
        r << "\nDistributions per region: `" << c.name << "_histograms.csv` (column `region`).\n";
    }
    return r.str();
}

// Scenes with nozzles: how the jet arrives on each logged component.
std::string jet_sections(const std::vector<ComponentAnalysis>& parts, const ReportContext& x) {
    std::ostringstream r;
    bool first = true;
    for (const ComponentAnalysis& c : parts) {
        if (!c.jet || c.jet->impacts() == 0) continue;
        const JetStreamStats& j = *c.jet;
        if (first) {
            r << "\n## The jet\n\n";
            for (const auto& [name, eps] : x.flow_rate_eps)
                r << "Nozzle " << name << ": dimensionless flow rate eps = r_m D / (v0 m_shot) = " << fmt(eps, 4) << ".\n";
            if (x.shot_shot_impacts) r << "Shot-shot collisions: " << *x.shot_shot_impacts << ".\n";
            r << "\n| component | impacts | at >= 90 % of v0 | steady share | steady after (impacts) |"
              << " keeping >= 90 % of the jet's normal speed |\n|---|---|---|---|---|---|\n";
            first = false;
        }
        const auto steady = j.steady_after();
        r << "| " << c.name << " | " << j.impacts() << " | " << fmt(100.0 * j.total().fast_share(), 3) << " % | "
          << fmt(100.0 * j.steady_fast_share(), 3) << " % | " << (steady ? std::to_string(*steady) : std::string("not reached")) << " | "
          << (c.jet_normal_meaningful ? fmt(100.0 * j.total().normal_kept_share(), 3) + " %" : std::string("(several nozzles or a moving part)"))
          << " |\n";
    }
    if (!first)
        r << "\nv0 = " << fmt(parts.front().jet->v0_m_per_s()) << " m/s (the nozzles' exit speed, rate-weighted). A shot arriving with "
          << "at least 90 % of v0 met nothing on its way; the share falls as the jet crowds (rebounding shot in its path). "
          << "Steady: from that impact on, every window of " << parts.front().jet->window() << " impacts holds its share within 3 standard errors of the "
          << "second half's. Per window: `<component>_jet.csv`; impact angles: `<component>_histograms.csv`.\n";
    return r.str();
}

// A shot mix: what each size brings to each logged component.
std::string size_sections(const std::vector<ComponentAnalysis>& parts) {
    std::ostringstream r;
    bool first = true;
    for (const ComponentAnalysis& c : parts) {
        if (c.sizes.empty()) continue;
        if (first) {
            r << "\n## Shot sizes\n\nThe run peened with a mix: each impact's dent is its own shot's (eq. 10 with its diameter), "
                 "and its energy 1/2 m v_n^2 its own shot's mass.\n\n"
              << "| component | shot diameter (mm) | impacts | share of impacts | mean v_n (m/s) | mean dent (um) | share of the energy |\n"
              << "|---|---|---|---|---|---|---|\n";
            first = false;
        }
        std::vector<ComponentAnalysis::SizeTally> sizes = c.sizes;
        std::sort(sizes.begin(), sizes.end(), [](const auto& a, const auto& b) { return a.diameter_m > b.diameter_m; });
        double energy = 0.0;
        for (const auto& z : sizes) energy += z.energy_J;
        for (const auto& z : sizes) {
            const double n = static_cast<double>(z.impacts);
            r << "| " << c.name << " | " << fmt(z.diameter_m * 1e3, 4) << " | " << z.impacts << " | " << fmt(100.0 * n / static_cast<double>(c.impacts), 3)
              << " % | " << fmt(z.speed_sum / n) << " | " << (c.coverage ? fmt(z.dent_sum / n * 1e6) : std::string("no yield_stress")) << " | "
              << fmt(energy > 0.0 ? 100.0 * z.energy_J / energy : NAN, 3) << " % |\n";
        }
    }
    return r.str();
}

}  // namespace

std::string analysis_summary_table(const std::vector<ComponentAnalysis>& parts, double duration) {
    std::ostringstream r;
    r << "| component | impacts | per s | mean v_n (m/s) | mean dent (um) | coverage | Avrami k (1/s) | time to 98 % (s) |\n";
    r << "|---|---|---|---|---|---|---|---|\n";
    for (const ComponentAnalysis& c : parts) {
        const double n = static_cast<double>(c.impacts);
        const double mean_v = c.impacts ? c.speed_sum / n : NAN;
        const double mean_d = c.impacts && c.coverage ? c.dent_sum / n * 1e6 : NAN;
        std::string k, t98, cov = "no yield_stress";
        if (c.coverage) {
            cov = fmt(100.0 * c.coverage->coverage(), 3) + " %";
            const AvramiFit fit = fit_avrami(c.curve);
            if (fit.points_used > 0 && fit.k_per_s > 0.0) {
                k = fmt(fit.k_per_s) + " +- " + fmt(fit.k_standard_error_per_s, 2);
                t98 = fmt(fit.time_to_98_percent_s) + (fit.extrapolated ? " (extrapolated)" : "");
            }
        }
        r << "| " << c.name << " | " << c.impacts << " | " << fmt(n / duration) << " | " << fmt(mean_v) << " | " << fmt(mean_d) << " | "
          << cov << " | " << k << " | " << t98 << " |\n";
    }
    return r.str();
}

std::string analysis_report(const SceneDescription& scene, const std::vector<ComponentAnalysis>& parts, const ReportContext& x) {
    std::ostringstream r;
    r << "# peensim analysis: " << (scene.name.empty() ? x.run_dir.string() : scene.name) << "\n\n";
    r << "Run: `" << x.run_dir.string() << "`, " << fmt(x.duration_s) << " s of peening simulated"
      << (x.finished ? "" : " (the run did not finish: its impact log is partial)") << ".\n";
    if (x.truncated) r << "The impact log ended inside a row (a run killed mid-write): that row was left out.\n";
    r << "\n" << analysis_summary_table(parts, x.duration_s);
    r << "\nCoverage follows SAE J2277: the area fraction covered by at least one dent, each dent of diameter "
         "phi = D (8 rho v_n^2 / (9 sigma_y))^(1/4) (eq. 10), sampled on a grid of spacing a fifth of the dent at 1 m/s; "
         "98 % counts as full coverage, its time from the fit C(t) = 1 - exp(-k t).\n\nFiles (per component): "
         "`<component>_triangles.csv` (per-triangle fields), `<component>_coverage.csv` (coverage vs time), "
         "`<component>_histograms.csv` (normal speed, impact angle, dent diameter; whole component and per region), "
         "`<component>.vtp` (the mesh with the per-triangle fields as cell data, for ParaView), `<component>_impacts.vtp` "
         "(the impacts as points with their relative velocity, normal speed and time), `<component>_regions.csv` (the "
         "scene's regions of the component, each triangle in the region holding its centroid), `<component>_almen.csv` "
         "(Almen strips: dose, dents and arc height vs time).\n";
    r << region_tables(parts, x.duration_s);
    r << almen_report_sections(parts, x.duration_s);
    r << jet_sections(parts, x);
    r << size_sections(parts);
    if (!x.pngs.empty()) r << "\n## Plots\n\n";
    for (const std::string& png : x.pngs) {
        const std::string name = fs::path(png).filename().string();
        const std::string stem = name.substr(0, name.size() - 4);
        const std::string kind = stem.substr(stem.rfind('_') + 1);
        r << "![" << kind << "](" << name << ")\n\n";
    }
    if (!x.plot_note.empty()) r << (x.pngs.empty() ? "\n" : "") << "Plots: " << x.plot_note << ".\n";
    return r.str();
}

}  // namespace peensim
