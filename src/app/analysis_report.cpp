#include "app/analysis_report.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "analysis/region_stats.h"
#include "app/almen_analysis.h"
#include "app/analysis_format.h"
#include "app/coverage_verdict.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// "1500 s (25 min)": seconds, and minutes or hours when that reads better.
std::string duration_text(double s) {
    if (std::isinf(s)) return "never at this rate";
    std::string text = fmt(s) + " s";
    if (s >= 7200.0) return text + " (" + fmt(s / 3600.0, 3) + " h)";
    if (s >= 120.0) return text + " (" + fmt(s / 60.0, 3) + " min)";
    return text;
}

std::string percent(double fraction, int digits = 3) { return std::isfinite(fraction) ? fmt(100.0 * fraction, digits) + " %" : ""; }

// "540-680 s" (an unbounded upper end: "540 s or more").
std::string interval_text(double low, double high) {
    if (std::isinf(high)) return fmt(low) + " s or more";
    return fmt(low) + "-" + fmt(high) + " s";
}

// Per component with regions: one table row per region.
std::string region_tables(const std::vector<ComponentAnalysis>& parts, double duration) {
    std::ostringstream r;
    for (const ComponentAnalysis& c : parts) {
        if (c.regions.empty()) continue;
        r << "\n### Regions of " << c.name
          << "\n\n| region | area (mm2) | peened (mm2) | impacts | per mm2 per s | mean v_n (m/s) | energy (J/m2) | coverage "
             "| Avrami k (1/s) | time to 98 % [95 %] | x the analysed time |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
        for (std::size_t k = 0; k < c.regions.size(); ++k) {
            const RegionStats s = region_stats(c.regions, k, c.region_tallies[k], c.coverage.get(), c.peened, duration);
            r << "| " << c.regions.name(k) << (c.regions.excluded(k) ? " (excluded)" : "") << " | " << fmt(s.area_m2 * 1e6) << " | "
              << fmt(s.peened_area_m2 * 1e6) << " | " << s.impacts << " | " << fmt(s.impacts_per_mm2_s) << " | " << fmt(s.mean_normal_speed)
              << " | " << fmt(s.energy_per_area) << " | " << percent(s.coverage) << " | ";
            const bool fitted = !c.region_outlooks.empty() && c.region_outlooks[k].fitted && !c.regions.excluded(k);
            if (fitted) {
                const CoverageOutlook& o = c.region_outlooks[k];
                r << fmt(o.k_per_s) << " | " << fmt(o.time_to_98_s) << " s [" << interval_text(o.time_to_98_low_s, o.time_to_98_high_s)
                  << "] | " << fmt(o.run_multiple, 3) << " |\n";
            } else {
                r << " | | |\n";
            }
        }
        r << "\nA region counts each triangle with the share of its area inside, and each impact by its point. Coverage is over "
             "the peened area (reachable, not excluded); an excluded region's over its whole area, for information. Per region: `"
          << c.name << "_regions.csv`, coverage against time `" << c.name << "_region_coverage.csv`, distributions `" << c.name
          << "_histograms.csv`; `peensim render-regions "
          << "<run>` draws them.\n";
    }
    return r.str();
}

// The decision a chamber designer needs for each part with coverage: is it reached, where not,
// when will it be, and what peening (and simulating) it takes.
std::string verdict_sections(const std::vector<ComponentAnalysis>& parts, const ReportContext& x) {
    std::ostringstream r;
    const double analysed = x.window.length_s();
    for (const ComponentAnalysis& c : parts) {
        if (!c.coverage) continue;
        const PeenedAreas areas = peened_areas(c);
        const CoverageOutlook& o = c.outlook;
        r << "\n## " << c.name << ": is coverage reached?\n\n";
        r << "- **Coverage now: " << percent(o.coverage) << "** of the peened area (" << fmt(areas.peened_m2 * 1e6) << " of "
          << fmt(areas.total_m2 * 1e6) << " mm2";
        if (areas.unreachable_m2 > 0.0)
            r << "; " << fmt(areas.unreachable_m2 * 1e6) << " mm2 (" << percent(areas.unreachable_m2 / areas.total_m2, 2)
              << ") no shot can reach, left out";
        if (areas.excluded_m2 > 0.0)
            r << "; " << fmt(areas.excluded_m2 * 1e6) << " mm2 (" << percent(areas.excluded_m2 / areas.total_m2, 2) << ") excluded";
        r << "). " << percent(share_below(c, x.window.target_coverage)) << " of the peened area is below the target of "
          << percent(x.window.target_coverage) << ".\n";
        if (o.fitted) {
            r << "- **Time to 98 %: " << duration_text(o.time_to_98_s) << "** (95 % interval "
              << interval_text(o.time_to_98_low_s, o.time_to_98_high_s) << "; Avrami k = " << fmt(o.k_per_s) << " 1/s +- "
              << fmt(100.0 * o.k_relative_se, 2) << " %)";
            if (o.run_multiple > 1.0)
                r << ", extrapolated from " << percent(o.coverage) << " to 98 %: " << fmt(o.run_multiple, 3) << "x the analysed "
                  << fmt(analysed) << " s";
            r << ".\n";
        } else {
            r << "- **Time to 98 %: not known**: " << (o.coverage >= 1.0 ? "fully covered already" : "no dent on the peened area yet")
              << ".\n";
        }
        if (c.regions.empty()) {
            r << "- **Everywhere: not known.** The part has no regions, and a whole-part time hides its least-peened places (on "
                 "the shipped gear the teeth's times span ~4x). Define regions (`sectors` for teeth, `facing` for flanks and end "
                 "faces, `distance_to_axis` for a bore) and check them with `peensim render-regions`.\n";
            continue;
        }
        const Everywhere e = everywhere(c);
        if (e.counted == 0) {
            r << "- **Everywhere:** every region is excluded or out of reach.\n";
            continue;
        }
        const std::string least = c.regions.name(static_cast<std::size_t>(e.least_covered));
        r << "- **Everywhere:** the least-covered region, **" << least << "**, reaches 98 % last: **" << duration_text(e.time_to_98_s)
          << "**";
        if (std::isfinite(e.time_to_98_s))
            r << (std::isfinite(e.time_to_98_high_s) ? " (up to " + duration_text(e.time_to_98_high_s) + " at 95 %)"
                                                     : std::string(" (at 95 %, with no upper bound yet: a region has too few impacts)"));
        r << ".";
        if (std::isfinite(e.time_to_98_s)) {
            const double needed = std::ceil(e.time_to_98_s);
            r << " To reach 98 % everywhere: " << fmt(needed, 8) << " s of peening";
            if (x.wall_per_simulated_s)
                r << "; simulating it takes about " << duration_text(needed * *x.wall_per_simulated_s) << " here (this run's pace)";
            r << ":\n\n      peensim run " << (x.run_dir / "scene.resolved.yaml").string() << " -o " << x.run_dir.string()
              << "-98 --set \"process.duration=" << fmt(needed, 8) << " s\" --no-render\n\n";
        } else {
            r << " It has had no impact: no peening time covers it at this rate; change the chamber, the part's position or "
                 "its motion.\n";
        }
        r << "- **Uniformity:** the slowest region's rate over the mean rate, " << fmt(e.uniformity, 3) << " (1: even); coverage now "
          << percent(e.coverage_min) << " in the least-covered region, " << percent(e.coverage_mean) << " over the " << e.counted
          << " regions counted.\n";
        for (const auto& [name, png] : x.least_covered_pngs)
            if (name == c.name) r << "\n![" << c.name << ": the least-covered region, " << least << "](" << png << ")\n";
    }
    if (!x.picture_note.empty()) r << "\nPictures: " << x.picture_note << ".\n";
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
          << (c.jet_normal_meaningful ? fmt(100.0 * j.total().normal_kept_share(), 3) + " %"
                                      : std::string("(several nozzles or a moving part)"))
          << " |\n";
    }
    if (!first)
        r << "\nv0 = " << fmt(parts.front().jet->v0_m_per_s()) << " m/s (the nozzles' exit speed, rate-weighted). A shot arriving with "
          << "at least 90 % of v0 met nothing on its way; the share falls as the jet crowds (rebounding shot in its path). "
          << "Steady: from that impact on, every window of " << parts.front().jet->window()
          << " impacts holds its share within 3 standard errors of the "
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
            r << "| " << c.name << " | " << fmt(z.diameter_m * 1e3, 4) << " | " << z.impacts << " | "
              << fmt(100.0 * n / static_cast<double>(c.impacts), 3) << " % | " << fmt(z.speed_sum / n) << " | "
              << (c.coverage ? fmt(z.dent_sum / n * 1e6) : std::string("no yield_stress")) << " | "
              << fmt(energy > 0.0 ? 100.0 * z.energy_J / energy : NAN, 3) << " % |\n";
        }
    }
    return r.str();
}

}  // namespace

std::string analysis_summary_table(const std::vector<ComponentAnalysis>& parts, const AnalysisWindow& window) {
    const double duration = window.length_s();
    std::ostringstream r;
    r << "| component | impacts | per s | mean v_n (m/s) | mean dent (um) | coverage | Avrami k (1/s) | time to 98 % (s) |\n";
    r << "|---|---|---|---|---|---|---|---|\n";
    for (const ComponentAnalysis& c : parts) {
        const double n = static_cast<double>(c.impacts);
        const double mean_v = c.impacts ? c.speed_sum / n : NAN;
        const double mean_d = c.impacts && c.coverage ? c.dent_sum / n * 1e6 : NAN;
        std::string k, t98, cov = "no yield_stress";
        if (c.coverage) {
            cov = percent(c.outlook.coverage);
            if (c.outlook.fitted) {
                k = fmt(c.outlook.k_per_s) + " +- " + fmt(c.outlook.k_relative_se * c.outlook.k_per_s, 2);
                t98 = fmt(c.outlook.time_to_98_s) +
                      (c.outlook.run_multiple > 1.0 ? " (extrapolated " + fmt(c.outlook.run_multiple, 3) + "x)" : "");
            }
        }
        r << "| " << c.name << " | " << c.impacts << " | " << fmt(n / duration) << " | " << fmt(mean_v) << " | " << fmt(mean_d) << " | "
          << cov << " | " << k << " | " << t98 << " |\n";
    }
    return r.str();
}

std::string analysis_report(const SceneDescription& scene, const std::vector<ComponentAnalysis>& parts, const ReportContext& x) {
    std::ostringstream r;
    const AnalysisWindow& w = x.window;
    r << "# peensim analysis: " << (scene.name.empty() ? x.run_dir.string() : scene.name) << "\n\n";
    r << "Run: `" << x.run_dir.string() << "`, " << fmt(x.log_duration_s) << " s of peening simulated"
      << (x.finished ? "" : " (the run did not finish: its impact log is partial)") << ".";
    if (w.from_s > 0.0 || w.to_s < x.log_duration_s)
        r << " Analysed: from " << fmt(w.from_s) << " s to " << fmt(w.to_s) << " s (" << fmt(w.length_s()) << " s; rates per this time).";
    if (w.min_speed_m_per_s > 0.0) r << " Impacts slower than " << fmt(w.min_speed_m_per_s) << " m/s are left out.";
    r << "\n";
    if (x.truncated) r << "The impact log ended inside a row (a run killed mid-write): that row was left out.\n";
    r << verdict_sections(parts, x);
    r << "\n## Summary\n\n" << analysis_summary_table(parts, w);
    r << "\nCoverage follows SAE J2277: the area fraction covered by at least one dent, each dent of diameter "
         "phi = D (8 rho v_n^2 / (9 sigma_y))^(1/4) (eq. 10), sampled on a grid of spacing a fifth of the dent at 1 m/s, over the "
         "peened area: facets no shot can reach (no room for a shot centre beside them, e.g. a bore an axle fills) and regions "
         "marked `exclude` are left out. 98 % counts as full coverage, its time from the fit C(t) = 1 - exp(-k t); the 95 % "
         "interval of k is the larger of the fit's and the scatter of the dent area delivered in 10 time batches.\n\nFiles (per "
         "component): `<component>_triangles.csv` (per-triangle fields, the same smoothed over a radius of the surface, the share a "
         "shot can reach, the excluded share and the region), `<component>_coverage.csv` (coverage vs time), "
         "`<component>_histograms.csv` (normal speed, impact angle, dent diameter; whole component and per region), "
         "`<component>.vtp` (the mesh with the per-triangle fields as cell data, for ParaView), `<component>_impacts.vtp` (the "
         "impacts as points with their relative velocity, normal speed and time), `<component>_coverage_series.pvd` (the coverage "
         "over time, for ParaView), `<component>_regions.csv` and `<component>_region_coverage.csv` (the scene's regions of the "
         "component), `<component>_almen.csv` (Almen strips: dose, dents and arc height vs time), `figures.json` (every figure, for "
         "programs), `open_in_paraview.py` (the whole run in ParaView: `paraview --script=open_in_paraview.py`).\n";
    r << region_tables(parts, w.length_s());
    r << almen_report_sections(parts, w.length_s());
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
