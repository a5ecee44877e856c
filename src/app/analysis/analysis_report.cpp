#include "app/analysis/analysis_report.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <thread>

#include "analysis/region_stats.h"
#include "app/analysis/almen_analysis.h"
#include "app/analysis/analysis_format.h"
#include "app/analysis/coverage_verdict.h"
#include "app/analysis/report_changes.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// The chance excess of everywhere (latest_crossing.h) is said when above this share of its time.
constexpr double kShownChanceExcess = 0.005;

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

// "98 %": the target as the headings write it.
std::string target_text(double target) { return fmt(100.0 * target, 4) + " %"; }

}  // namespace

std::string forecast_cell(const AreaForecast& f) {
    switch (f.status) {
        case AreaForecast::Status::reached:
            return "reached at " + fmt(f.time_s) + " s" + (f.seen_in_run ? " (the run's; after the window)" : "");
        case AreaForecast::Status::forecast: return fmt(f.time_s) + " s [" + interval_text(f.low_s, f.high_s) + "]";
        case AreaForecast::Status::too_short:
            return "too short to say (run " +
                   (std::isfinite(f.run_for_s) ? fmt(std::ceil(f.run_for_s), 6) + " s" : std::string("far longer")) + ")";
        case AreaForecast::Status::never: return "never at this rate";
        case AreaForecast::Status::none: return "";
    }
    return "";
}

namespace {

// A forecast as a sentence of the report, ending with a full stop.
std::string forecast_sentence(const AreaForecast& f, double analysed_s, const ReportContext& x) {
    std::ostringstream r;
    switch (f.status) {
        case AreaForecast::Status::reached:
            if (f.seen_in_run) {
                r << "**reached at " << duration_text(f.time_s)
                  << "**, as the run that watched it counted (`until_coverage_of`), after the " << fmt(analysed_s)
                  << " s analysed, where it stood at " << percent(f.coverage_now) << ".";
                break;
            }
            r << "**reached at " << duration_text(f.time_s) << "** of the " << fmt(analysed_s) << " s analysed.";
            break;
        case AreaForecast::Status::forecast:
            r << "**" << duration_text(f.time_s) << "** (95 % interval " << interval_text(f.low_s, f.high_s) << "), forecast from where "
              << "the dents landed in the " << fmt(analysed_s) << " s analysed (" << fmt(f.time_s / analysed_s, 3) << "x).";
            break;
        case AreaForecast::Status::too_short:
            r << "**too short to say** from " << fmt(analysed_s) << " s: the 95 % interval would be " << interval_text(f.low_s, f.high_s)
              << ". ";
            if (std::isfinite(f.run_for_s)) {
                r << "A run of about " << fmt(std::ceil(f.run_for_s), 6) << " s gives a number";
                if (x.wall_per_simulated_s)
                    r << " (about " << duration_text(f.run_for_s * *x.wall_per_simulated_s)
                      << " of wall time to simulate here, the analysis not counted)";
                r << ".";
            } else {
                r << "Some of it has had no impact near it yet: run longer.";
            }
            break;
        case AreaForecast::Status::never:
            r << "**never at this rate**: part of it has had no impact near it (within the forecast's radius); change the chamber, "
                 "the part's position or its motion, or run longer to see whether any shot reaches it.";
            break;
        case AreaForecast::Status::none: r << "not known: no dent on the peened area yet."; break;
    }
    return r.str();
}

// Per component with regions: one table row per region.
std::string region_tables(const std::vector<ComponentAnalysis>& parts, const AnalysisWindow& window) {
    std::ostringstream r;
    const double duration = window.length_s();
    for (const ComponentAnalysis& c : parts) {
        if (c.regions.empty()) continue;
        r << "\n### Regions of " << c.name
          << "\n\n| region | area (mm2) | peened (mm2) | out of reach (mm2) | impacts | per mm2 per s | mean v_n (m/s) "
             "| energy (J/m2) | coverage | time to "
          << target_text(window.target_coverage) << " [95 %] |\n|---|---|---|---|---|---|---|---|---|---|\n";
        for (std::size_t k = 0; k < c.regions.size(); ++k) {
            const RegionStats s = region_stats(c.regions, k, c.region_tallies[k], c.coverage.get(), duration);
            r << "| " << c.regions.name(k) << (c.regions.excluded(k) ? " (excluded)" : "") << " | " << fmt(s.area_m2 * 1e6) << " | "
              << fmt(s.peened_area_m2 * 1e6) << " | " << fmt(s.unreachable_area_m2 * 1e6) << " | " << s.impacts << " | "
              << fmt(s.impacts_per_mm2_s) << " | " << fmt(s.mean_normal_speed) << " | " << fmt(s.energy_per_area) << " | "
              << percent(s.coverage) << " | " << (c.coverage && k < c.forecast.regions.size() ? forecast_cell(c.forecast.regions[k]) : "")
              << " |\n";
        }
        r << "\nA region counts each coverage sample inside it and each impact by its point. Coverage is over the peened area "
             "(reachable, not excluded); an excluded region's over its reachable area, for information. Per region: `"
          << c.name << "_regions.csv`, coverage against time `" << c.name << "_region_coverage.csv`, distributions `" << c.name
          << "_histograms.csv`; `peensim render-regions <run>` draws them.\n";
    }
    return r.str();
}

// The command that peens until the target is reached everywhere (brute force), capped; on a
// machine of several cores, as that many replicas in rounds (design.md, "Until coverage: rounds").
std::string until_command(const ReportContext& x, double target, double cap_s, unsigned cores) {
    return "peensim run " + (x.run_dir / "scene.resolved.yaml").string() + " -o " + x.run_dir.string() + "-until --until-coverage \"" +
           fmt(100.0 * target, 4) + " %\" --set \"process.duration=" + fmt(std::ceil(cap_s), 8) + " s\"" +
           (x.watches_some_areas ? " --set \"process.until_coverage_of=[]\"" : "") + " --no-render" +
           (cores > 1 ? " --replicas " + std::to_string(cores) : std::string());
}

// The decision a chamber designer needs for each part with coverage: is it reached, where not,
// when will it be, and what peening (and simulating) it takes.
std::string verdict_sections(const std::vector<ComponentAnalysis>& parts, const ReportContext& x) {
    std::ostringstream r;
    const double analysed = x.window.length_s();
    const double target = x.window.target_coverage;
    const std::string goal = target_text(target);
    for (const ComponentAnalysis& c : parts) {
        if (!c.coverage) continue;
        const PeenedAreas areas = peened_areas(c);
        const AreaForecast& w = c.forecast.whole;
        r << "\n## " << c.name << ": how long to peen to " << goal << "\n\n";
        if (!(areas.peened_m2 > 0.0)) {
            // Nothing to measure coverage on: said in words (the figures would be empty, the plot absent).
            r << "- **No peened area: coverage is not measured.** All " << fmt(areas.total_m2 * 1e6) << " mm2 of " << c.name
              << " are left out: " << fmt(areas.excluded_m2 * 1e6) << " mm2 in regions marked `exclude`, "
              << fmt(areas.unreachable_m2 * 1e6) << " mm2 out of the shot's reach. Its impacts are still counted (below); to "
              << "measure coverage, remove `exclude` from a region of it.\n";
            r << unreachable_section(c, x);
            continue;
        }
        r << "- **Coverage now: " << percent(w.coverage_now) << "** of the peened area (" << fmt(areas.peened_m2 * 1e6) << " of "
          << fmt(areas.total_m2 * 1e6) << " mm2";
        if (areas.unreachable_m2 > 0.0)
            r << "; " << fmt(areas.unreachable_m2 * 1e6) << " mm2 (" << percent(areas.unreachable_m2 / areas.total_m2, 2)
              << ") no shot can reach, left out: see below";
        if (areas.excluded_m2 > 0.0)
            r << "; " << fmt(areas.excluded_m2 * 1e6) << " mm2 (" << percent(areas.excluded_m2 / areas.total_m2, 2) << ") excluded";
        r << "). " << percent(share_below(c, target)) << " of the peened area is below " << goal << ".\n";
        r << "- **Time to " << goal << "** (the whole peened area): " << forecast_sentence(w, analysed, x) << "\n";
        if (const ForecastSummary& fs = c.forecast.summary; fs.rate_drifts)
            r << "- **The impact rate drifted during the window:** " << (fs.rate_change > 0.0 ? "+" : "") << percent(fs.rate_change, 2)
              << " from its first batch to its last (a load that grows, as a source feeding a closed chamber, or settles). The "
                 "forecasts take the window's mean rate for all the time to come: with a rising rate they are late, with a "
                 "falling one early. Analyse a window where the rate is steady (`peensim analyze RUN --from ...`), or run to "
                 "the target (`--until-coverage`).\n";
        if (x.replicas && w.status == AreaForecast::Status::forecast)
            r << "- **A run as " << x.replicas->windows << " replicas:** each of its windows (the shortest "
              << fmt(x.replicas->shortest_window_s, 3)
              << " s) follows a start from rest, logged from its measured warm-up on. Short windows scatter more: on the "
                 "shipped gear (20 seeds), 4 windows of 15 s gave the whole part's time with 1.6 times one trajectory's scatter "
                 "between seeds (its interval held the truth 16 of 20 times) and everywhere 2.5 % earlier, while 2 windows "
                 "of 30 s agreed with one trajectory (docs/design.md, \"Every core for one run\"). For the forecasts, prefer "
                 "fewer replicas with longer windows.\n";
        const Everywhere e = everywhere(c);
        if (c.regions.empty()) {
            r << "- **Everywhere: not known.** The part has no regions, and a whole-part time hides its least-peened places (on "
                 "the shipped gear the slowest tooth needs 1.4x the whole gear's time). Define regions (`sectors` for teeth, "
                 "`facing` for flanks and end faces, `distance_to_axis` for a bore) and check them with `peensim render-regions`.\n";
        } else if (e.counted == 0) {
            r << "- **Everywhere:** every region is excluded or out of reach.\n";
        } else {
            const std::string least = slowest_area_name(c, e.slowest);
            r << "- **Everywhere** (every region at " << goal << "): " << forecast_sentence(e.time, analysed, x);
            if (!least.empty()) r << " The last region there: **" << least << "**.";
            if (const double excess = c.forecast.summary.everywhere_chance_excess_s;
                e.time.status == AreaForecast::Status::forecast && excess > kShownChanceExcess * e.time.time_s)
                r << " Several regions are forecast alike, and the latest of forecasts alike is late by chance (the one that came "
                     "out latest is the one whose estimate ran late): that chance adds "
                  << fmt(excess, 3) << " s to the latest here, and everywhere takes it off. So a region's own figure can exceed this "
                  << "one; the upper end covers every region's.";
            r << "\n";
            if (std::isfinite(e.uniformity))
                r << "- **Uniformity:** " << fmt(e.uniformity, 3) << " (" << fmt(e.uniformity_low, 3) << "-" << fmt(e.uniformity_high, 3)
                  << "): the whole part's time over everywhere's (1: the slowest region is no slower than the part). Coverage now "
                  << percent(e.coverage_min) << " in the least-covered region, " << percent(e.coverage_mean) << " over the " << e.counted
                  << " regions counted.\n";
            // Peening to the target everywhere: the forecast's upper end, or brute force.
            const AreaForecast& t = e.time;
            if (t.status == AreaForecast::Status::forecast) {
                r << "\n  To peen every region to " << goal << ", peen " << fmt(std::ceil(t.high_s), 8)
                  << " s (the interval's upper end). To see it rather than forecast it, run until every region reaches it";
                const unsigned cores = std::thread::hardware_concurrency();
                if (x.wall_per_simulated_s)
                    r << " (about " << duration_text(t.time_s * *x.wall_per_simulated_s)
                      << " of wall time at this run's pace, the analysis not counted)";
                if (cores > 1) r << "; the command runs it as " << cores << " replicas, one a core of this machine, which share that time";
                r << ":\n\n      " << until_command(x, target, 1.5 * t.high_s, cores) << "\n";
            }
            for (const auto& [name, png] : x.slowest_region_pngs)
                if (name == c.name) r << "\n![" << c.name << ": the slowest region, " << least << "](" << png << ")\n";
        }
        r << unreachable_section(c, x);
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
          << "Steady: from that impact on (windows of " << parts.front().jet->window()
          << " impacts; the warm-up that, cut off, leaves the most precise mean share: MSER); steady share: the "
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
    const std::string goal = target_text(window.target_coverage);
    std::ostringstream r;
    r << "| component | impacts | per s | mean v_n (m/s) | mean dent (um) | coverage | time to " << goal
      << " [95 %] | everywhere [95 %] |\n";
    r << "|---|---|---|---|---|---|---|---|\n";
    for (const ComponentAnalysis& c : parts) {
        const double n = static_cast<double>(c.impacts);
        const double mean_v = c.impacts ? c.speed_sum / n : NAN;
        const double mean_d = c.impacts && c.coverage ? c.dent_sum / n * 1e6 : NAN;
        std::string cov = "no yield_stress", whole, every;
        if (c.coverage) {
            cov = percent(c.coverage->coverage());
            whole = forecast_cell(c.forecast.whole);
            if (!c.regions.empty()) every = forecast_cell(c.forecast.everywhere);
        }
        r << "| " << c.name << " | " << c.impacts << " | " << fmt(n / duration) << " | " << fmt(mean_v) << " | " << fmt(mean_d) << " | "
          << cov << " | " << whole << " | " << every << " |\n";
    }
    return r.str();
}

namespace {

// A rotating part is analysed over whole turns: what the window holds of them, and the run that
// would fix a window too short or not whole.
std::string turn_sentences(const AnalysisWindow& w) {
    if (w.turn_s <= 0.0) return "";
    std::ostringstream r;
    const std::string turn = fmt(w.turn_s, 4) + " s";
    if (w.shorter_than_a_turn()) {
        r << "\n**The window is " << fmt(w.turns(), 2) << " of a turn of the rotating part (a turn takes " << turn
          << ")**: the sides that have not faced the sonotrode yet are not peened like the others, so no region, no uniformity and no "
             "time to the target here is the part's. Run at least "
          << fmt(w.from_s + w.turn_s, 4)
          << " s (a whole turn): `--set \"process.duration=" << fmt(std::ceil((w.from_s + w.turn_s) * 1000.0) / 1000.0, 8) << " s\"`.\n";
    } else if (w.ends_at_target) {
        const double fraction = w.turns() - std::floor(w.turns());
        if (fraction > 1e-9 && fraction < 1.0 - 1e-9)
            r << "\nThe run peened until every area reached its target (`--until-coverage`) and ended there, " << fmt(w.turns(), 4)
              << " turns of the rotating part (" << turn
              << " each): analysed to that end, the part of the last turn included. Cut back to whole turns, the window would "
                 "leave out the impacts that reached the target.\n";
    } else if (w.to_s < w.asked_to_s - 1e-9 * w.turn_s) {
        const double whole = std::round(w.turns());
        r << "\nAnalysed over " << fmt(whole, 6) << " whole turn" << (whole == 1.0 ? "" : "s") << " of the rotating part (" << turn
          << (whole == 1.0 ? "" : " each") << "): to " << fmt(w.to_s) << " s; the last " << fmt(w.asked_to_s - w.to_s, 3)
          << " s, part of a turn, is left out, as it would weigh the side that faced the sonotrode in it more than the others.";
        // A run that ended where its watched areas reached the target ends there again whatever its
        // duration: no longer run to advise.
        if (w.seen_reached_after.empty())
            r << " A run of " << fmt(std::ceil((w.from_s + (whole + 1.0) * w.turn_s) * 1000.0) / 1000.0, 8) << " s (" << fmt(whole + 1.0, 6)
              << " turns) uses every impact.";
        else {
            r << " The run peened until the areas it watched reached the target (`until_coverage_of`) and ended there; it counted";
            for (std::size_t k = 0; k < w.seen_reached_after.size(); ++k)
                r << (k == 0 ? " " : (k + 1 == w.seen_reached_after.size() ? " and " : ", ")) << w.seen_reached_after[k].first
                  << " reaching it at " << fmt(w.seen_reached_after[k].second) << " s";
            r << ", in that part of a turn: those times are the run's, the other areas' forecasts read the whole turns.";
        }
        r << "\n";
    } else if (w.to_given) {
        const double fraction = w.turns() - std::floor(w.turns());
        // A part of a turn matters while it is a noticeable share of the window.
        if (fraction > 0.02 && fraction < 0.98 && w.turns() < 20.0)
            r << "\n**--to makes the window " << fmt(w.turns(), 3) << " turns of the rotating part** (" << turn
              << " each): the part of the last turn weighs the side that faced the sonotrode in it more than the others. Analyse a "
                 "whole number: `--to "
              << fmt(w.from_s + std::max(1.0, std::floor(w.turns())) * w.turn_s, 6) << " s`.\n";
    }
    return r.str();
}

// The scene's name, and the --set options the run changed it with: the title says what was run.
std::string report_title(const SceneDescription& scene, const ReportContext& x) {
    std::string title = scene.name.empty() ? x.run_dir.string() : scene.name;
    if (!x.overrides.empty()) {
        title += " (run with";
        for (const std::string& o : x.overrides) title += " --set " + o;
        title += ")";
    }
    return title;
}

}  // namespace

std::string analysis_report(const SceneDescription& scene, const std::vector<ComponentAnalysis>& parts, const ReportContext& x) {
    std::ostringstream r;
    const AnalysisWindow& w = x.window;
    r << "# peensim analysis: " << report_title(scene, x) << "\n\n";
    r << "Run: `" << x.run_dir.string() << "`, " << fmt(x.log_duration_s) << " s of peening simulated"
      << (x.finished ? "" : " (the run did not finish: its impact log is partial)") << ".";
    if (w.from_s > 0.0 || w.to_s < x.log_duration_s)
        r << " Analysed: from " << fmt(w.from_s) << " s to " << fmt(w.to_s) << " s (" << fmt(w.length_s()) << " s; rates per this time).";
    if (w.min_speed_m_per_s > 0.0) r << " Impacts slower than " << fmt(w.min_speed_m_per_s) << " m/s are left out.";
    r << "\n";
    if (x.truncated) r << "The impact log ended inside a row (a run killed mid-write): that row was left out.\n";
    r << turn_sentences(w);
    r << verdict_sections(parts, x);
    if (!x.views.empty() || !x.view_note.empty()) {
        r << "\n## The parts in 3D\n\n";
        if (!x.views.empty())
            r << "report.html shows each part in 3D, in its own frame: choose what colours it (of coverage, raw and smoothed, with the "
                 "target marked on the colour bar; the impact density and the mean normal speed, smoothed as in the tables; the time its "
                 "region takes to the target; the region: those the part has; grey where a field has no value, e.g. coverage out of "
                 "reach or excluded), drag to turn it, and click on it to read the values there.\n\n";
        for (const std::string& part : x.views) r << part_view_marker(part) << "\n";
        if (!x.view_note.empty()) r << (x.views.empty() ? "" : "\n") << x.view_note << "\n";
    }
    r << "\n## Summary\n\n" << analysis_summary_table(parts, w);
    r << "\nCoverage follows SAE J2277: the area fraction covered by at least one dent, each dent of diameter "
         "phi = D (8 rho v_n^2 / (9 sigma_y))^(1/4) (eq. 10), sampled on a grid of spacing a fifth of the dent at 1 m/s, over the "
         "peened area: the samples no shot can touch (no room for a shot centre a radius away along the normal, e.g. a bore an "
         "axle fills) and regions marked `exclude` are left out. The time to the target is forecast point by point: every "
         "uncovered sample stays uncovered with probability exp(-mu tau), mu its local rate of dents (their area per area around "
         "it, from the impacts on faces, smoothed over the radius the extrapolation allows, counting noise removed), and the "
         "area's time is when the expected uncovered share falls to 1 - target; its 95 % interval from a jackknife over 10 time "
         "batches, widened by the smoothing's bias (the forecast at twice the radius). See docs/user-guide.md, "
         "\"How long to peen\".\n\nFiles "
         "(per "
         "component): `<component>_triangles.csv` (per-triangle fields, the same smoothed over a radius of the surface, the share a "
         "shot can reach, the excluded share and the region), `<component>_coverage.csv` (coverage vs time), "
         "`<component>_histograms.csv` (normal speed, impact angle, dent diameter; whole component and per region), "
         "`<component>.vtp` (the mesh with the per-triangle fields as cell data, for ParaView), `<component>_impacts.vtp` (the "
         "impacts as points with their relative velocity, normal speed and time), `<component>_coverage_series.pvd` (the coverage "
         "over time, for ParaView), `<component>_regions.csv` and `<component>_region_coverage.csv` (the scene's regions of the "
         "component), `<component>_almen.csv` (Almen strips: dose, dents and arc height vs time), `figures.json` (every figure, for "
         "programs), `open_in_paraview.py` (the whole run in ParaView: `paraview --script=open_in_paraview.py`).\n";
    r << region_tables(parts, w);
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
    r << changes_section(scene, parts, x);
    return r.str();
}

}  // namespace peensim
