#include "app/sweep/sweep_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "analysis/sample_mean.h"
#include "analysis/student_t.h"
#include "app/analysis/analysis_format.h"
#include "app/analysis/analysis_plots.h"
#include "app/analysis/report_views.h"
#include "app/component_analysis.h"
#include "app/sweep/sweep_views.h"
#include "output/atomic_file.h"
#include "output/markdown_html.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// A forecast of one run (figures.json's time_to_target objects): the time to the target and the
// half-width of its 95 % interval (the wider side; infinite when it has no upper end), or why there
// is none ("too short: run 600 s", "never at this rate: part of it has had no impact near it (a longer run may find one)").
struct RunForecast {
    double time_s = NAN, half_width_s = NAN;
    std::string missing;
    double run_for_s = 0.0;  // too short: how long a run would tell
};

// What one finished run gives the comparison.
struct RunFigures {
    double rate = NAN, mean_vn = NAN, p90_vn = NAN, coverage = NAN, almen = NAN, almen_intensity = NAN, share_below = NAN;
    double uniformity = NAN, uniformity_half_width = NAN;
    RunForecast whole, everywhere, slowest;  // slowest: the slowest named region's
    std::string slowest_region;
    double target = NAN;  // the target coverage the forecasts aim at (0..1)
    std::vector<double> batch_rate, batch_vn;
    struct Region {
        double rate = NAN, coverage = NAN;
        RunForecast time;
    };
    std::map<std::string, Region> regions;
};

double value_or_nan(const nlohmann::json& j, const char* key) {
    const auto it = j.find(key);
    return it != j.end() && it->is_number() ? it->get<double>() : NAN;
}

std::vector<double> numbers(const nlohmann::json& j, const char* key) {
    std::vector<double> out;
    const auto it = j.find(key);
    if (it != j.end() && it->is_array())
        for (const auto& x : *it)
            if (x.is_number()) out.push_back(x.get<double>());
    return out;
}

RunForecast forecast_of(const nlohmann::json& j, const char* key) {
    RunForecast f;
    const auto it = j.find(key);
    if (it == j.end() || !it->is_object()) {
        f.missing = "not analysed";
        return f;
    }
    const std::string status = it->value("status", "none");
    if (status == "reached" || status == "forecast") {
        f.time_s = value_or_nan(*it, "time_s");
        const double low = value_or_nan(*it, "low_s"), high = value_or_nan(*it, "high_s");  // high null: unbounded
        f.half_width_s = std::isfinite(high) ? std::max(high - f.time_s, f.time_s - low) : INFINITY;
    } else if (status == "too_short") {
        const double run_for = value_or_nan(*it, "run_for_s");
        f.missing = std::isfinite(run_for) ? "too short: run " + fmt(run_for, 3) + " s" : "too short";
        f.run_for_s = std::isfinite(run_for) ? run_for : 0.0;
    } else if (status == "never") {
        f.missing = "never at this rate: part of it has had no impact near it (a longer run may find one)";
    } else {
        f.missing = "no coverage";
    }
    return f;
}

// The run's figures for `component` ("" = the first logged), or none if it has not finished.
std::optional<RunFigures> read_run(const std::string& dir, std::string& component) {
    std::ifstream summary_in(dir + "/summary.json"), figures_in(dir + "/analysis/figures.json");
    if (!summary_in || !figures_in) return std::nullopt;
    const auto summary = nlohmann::json::parse(summary_in, nullptr, false);
    const auto figures = nlohmann::json::parse(figures_in, nullptr, false);
    if (summary.is_discarded() || figures.is_discarded() || !summary.value("finished", false)) return std::nullopt;
    const auto& components = figures.value("components", nlohmann::json::array());
    const nlohmann::json* c = nullptr;
    for (const auto& x : components)
        if (component.empty() || x.value("component", "") == component) {
            c = &x;
            break;
        }
    if (c == nullptr) return std::nullopt;
    component = c->value("component", "");
    RunFigures r;
    r.target = value_or_nan(figures, "target_coverage");
    r.rate = value_or_nan(*c, "impact_rate_per_s");
    r.mean_vn = value_or_nan(*c, "mean_vn_mps");
    r.coverage = value_or_nan(*c, "coverage");
    r.share_below = value_or_nan(*c, "share_below_target");
    r.whole = forecast_of(*c, "time_to_target");
    r.everywhere = forecast_of(*c, "time_to_target_everywhere");
    if (const auto u = c->find("uniformity"); u != c->end() && u->is_object()) {
        r.uniformity = value_or_nan(*u, "value");
        const double low = value_or_nan(*u, "low"), high = value_or_nan(*u, "high");
        r.uniformity_half_width = std::max(high - r.uniformity, r.uniformity - low);
    }
    r.almen = value_or_nan(*c, "almen_dose_J_per_m2");
    r.almen_intensity = value_or_nan(*c, "almen_predicted_intensity_m");
    r.batch_rate = numbers(*c, "batch_impact_rate_per_s");
    r.batch_vn = numbers(*c, "batch_mean_vn_mps");
    for (const auto& s : summary.value("normal_speed", nlohmann::json::array()))
        if (s.value("component", "") == component) r.p90_vn = value_or_nan(s, "p90_normal_speed_mps");
    // The slowest named region: the latest time among the counted regions; a region without a
    // number (too short, never) leaves the slowest unknown, and says why.
    r.slowest.missing = "no regions";
    for (const auto& g : c->value("regions", nlohmann::json::array())) {
        RunFigures::Region& region = r.regions[g.value("region", "")];
        region.rate = value_or_nan(g, "impact_rate_per_s");
        region.coverage = value_or_nan(g, "coverage");
        region.time = forecast_of(g, "time_to_target");
        if (g.value("excluded", false) || region.time.missing == "no coverage") continue;
        const bool first = r.slowest.missing == "no regions";
        if (!region.time.missing.empty()) {
            if (first || r.slowest.missing.empty()) r.slowest = region.time, r.slowest_region = g.value("region", "");
        } else if (first || (r.slowest.missing.empty() && region.time.time_s > r.slowest.time_s)) {
            r.slowest = region.time, r.slowest_region = g.value("region", "");
        }
    }
    return r;
}

// A forecast over the variant's runs: with two or more, Student's t over the runs' times; with
// one, the run's own interval. A run without a number leaves the variant without one, saying why
// (the longest run any of them asks for).
SweepFigure forecast_figure(const std::vector<RunFigures>& runs, RunForecast RunFigures::*member) {
    std::vector<double> times;
    const RunForecast* missing = nullptr;
    for (const RunFigures& r : runs) {
        const RunForecast& f = r.*member;
        if (f.missing.empty())
            times.push_back(f.time_s);
        else if (missing == nullptr || f.run_for_s > missing->run_for_s)
            missing = &f;
    }
    if (missing != nullptr) return {std::nullopt, std::nullopt, missing->missing};
    if (times.empty()) return {};
    if (runs.size() > 1) return mean_with_ci95(times);
    const double half = (runs[0].*member).half_width_s;
    return {times[0], std::isfinite(half) ? std::optional<double>(half) : std::nullopt, ""};
}

// A figure over the variant's runs: with two or more, Student's t over the runs; with one,
// `single` (its batch means, or a standard error of its own), or no interval.
SweepFigure figure(const std::vector<RunFigures>& runs, double RunFigures::*member, const SweepFigure& single = {}) {
    std::vector<double> v;
    for (const RunFigures& r : runs) v.push_back(r.*member);
    const SampleMean s = sample_mean(v);
    if (s.count == 0) return {};
    if (runs.size() == 1) return {s.mean, single.ci95, ""};
    return mean_with_ci95(v);
}

std::string csv_cell(const std::optional<double>& x) {
    if (!x) return "";
    std::ostringstream s;
    s.precision(6);
    s << *x;
    return s.str();
}

std::string shown(const SweepFigure& f, double scale = 1.0, int digits = 4) {
    if (!f.mean) return "-";
    return fmt(*f.mean * scale, digits) + (f.ci95 ? " +- " + fmt(*f.ci95 * scale, 2) : "");
}

// A value's leading number ("30 rpm" -> 30), for the plots' x axis; NaN if it has none.
double leading_number(const std::string& value) {
    try {
        std::size_t used = 0;
        const double x = std::stod(value, &used);
        return used > 0 ? x : NAN;
    } catch (const std::exception&) {
        return NAN;
    }
}

// The unit written after a value's number, for the axis label ("30 rpm" -> " (rpm)"; none: "").
std::string unit_of(const std::string& value) {
    std::size_t used = 0;
    try {
        (void)std::stod(value, &used);
    } catch (const std::exception&) {
        return "";
    }
    const auto b = value.find_first_not_of(' ', used);
    return b == std::string::npos ? std::string() : " (" + value.substr(b) + ")";
}

// A variant's figures over its finished runs.
struct CompareRow {
    SweepFigure rate, mean_vn, p90_vn, coverage, almen, almen_intensity, whole, slowest, everywhere, uniformity, share_below;
    std::string slowest_region;  // the region slowest in most runs
    struct Region {
        SweepFigure rate, coverage, time;
    };
    std::map<std::string, Region> regions;
    std::size_t runs = 0;
};

// Every variant's row (the first logged part's, or `component`'s), the regions' names as met, and
// the target coverage the runs' forecasts aim at.
std::vector<CompareRow> variant_rows(const SweepPlan& plan, std::string& component, std::vector<std::string>& region_names,
                                     double& target) {
    // Every finished run, by variant.
    std::vector<std::vector<RunFigures>> runs(plan.variants.size());
    for (const SweepRun& run : plan.runs)
        if (auto r = read_run(run.dir, component)) runs[run.variant].push_back(*r);

    std::vector<CompareRow> rows(plan.variants.size());
    for (std::size_t v = 0; v < plan.variants.size(); ++v) {
        const std::vector<RunFigures>& rs = runs[v];
        CompareRow& row = rows[v];
        row.runs = rs.size();
        if (rs.empty()) continue;
        if (!std::isfinite(target)) target = rs[0].target;
        row.rate = figure(rs, &RunFigures::rate, mean_with_ci95(rs[0].batch_rate));
        row.mean_vn = figure(rs, &RunFigures::mean_vn, mean_with_ci95(rs[0].batch_vn));
        row.p90_vn = figure(rs, &RunFigures::p90_vn);
        row.coverage = figure(rs, &RunFigures::coverage);
        row.almen = figure(rs, &RunFigures::almen);
        row.almen_intensity = figure(rs, &RunFigures::almen_intensity);
        row.share_below = figure(rs, &RunFigures::share_below);
        const double u_half = rs[0].uniformity_half_width;
        row.uniformity =
            figure(rs, &RunFigures::uniformity, {std::nullopt, std::isfinite(u_half) ? std::optional<double>(u_half) : std::nullopt, ""});
        row.whole = forecast_figure(rs, &RunFigures::whole);
        row.slowest = forecast_figure(rs, &RunFigures::slowest);
        row.everywhere = forecast_figure(rs, &RunFigures::everywhere);
        std::map<std::string, int> slowest_votes;
        for (const RunFigures& r : rs)
            if (!r.slowest_region.empty()) ++slowest_votes[r.slowest_region];
        for (const auto& [name, votes] : slowest_votes)
            if (row.slowest_region.empty() || votes > slowest_votes[row.slowest_region]) row.slowest_region = name;
        for (const auto& [name, unused] : rs[0].regions) {
            (void)unused;
            if (std::find(region_names.begin(), region_names.end(), name) == region_names.end()) region_names.push_back(name);
            std::vector<double> rate, cov;
            std::vector<RunFigures> with_region;
            for (const RunFigures& r : rs) {
                const auto it = r.regions.find(name);
                if (it == r.regions.end()) continue;
                rate.push_back(it->second.rate), cov.push_back(it->second.coverage);
                with_region.push_back(r);
                with_region.back().whole = it->second.time;  // the region's forecast, read as a whole-part one
            }
            row.regions[name] = {mean_with_ci95(rate), mean_with_ci95(cov), forecast_figure(with_region, &RunFigures::whole)};
        }
    }
    return rows;
}

// comparison.csv's columns: every figure with the half-width of its 95 % interval.
struct CompareColumn {
    const char* name;
    SweepFigure CompareRow::*figure;
    bool compared;  // with a difference from the baseline and a verdict
};
constexpr CompareColumn kCompareColumns[] = {{"impact_rate_per_s", &CompareRow::rate, true},
                                             {"mean_vn_mps", &CompareRow::mean_vn, false},
                                             {"p90_vn_mps", &CompareRow::p90_vn, false},
                                             {"coverage", &CompareRow::coverage, true},
                                             {"time_to_target_s", &CompareRow::whole, true},
                                             {"slowest_region_time_to_target_s", &CompareRow::slowest, true},
                                             {"time_to_target_everywhere_s", &CompareRow::everywhere, true},
                                             {"uniformity", &CompareRow::uniformity, true},
                                             {"share_below_target", &CompareRow::share_below, true},
                                             {"almen_dose_J_per_m2", &CompareRow::almen, false},
                                             {"almen_predicted_intensity_m", &CompareRow::almen_intensity, false}};

}  // namespace

SweepFigure mean_with_ci95(const std::vector<double>& values) {
    const SampleMean s = sample_mean(values);
    if (s.count == 0) return {};
    if (s.count < 2) return {s.mean, std::nullopt, ""};
    return {s.mean, student_t_two_sided_quantile(0.05, static_cast<double>(s.count) - 1.0) * s.standard_error, ""};
}

SweepDifference compare_figures(const SweepFigure& a, const SweepFigure& b) {
    SweepDifference d;
    if (!a.mean || !b.mean) return {std::nullopt, "-"};
    d.delta = *a.mean - *b.mean;
    if (!a.ci95 || !b.ci95) {
        d.verdict = "-";
        return d;
    }
    d.verdict = std::abs(*d.delta) > std::hypot(*a.ci95, *b.ci95) ? "differs" : "within noise";
    return d;
}

SweepFigures read_sweep_figures(const SweepPlan& plan, const std::string& component) {
    SweepFigures out;
    out.component = component;
    std::vector<std::string> region_names;
    const std::vector<CompareRow> rows = variant_rows(plan, out.component, region_names, out.target_coverage);
    for (const CompareRow& r : rows) {
        SweepVariantFigures v;
        v.runs = r.runs;
        v.slowest_region = r.slowest_region;
        for (const CompareColumn& c : kCompareColumns) v.figures[c.name] = r.*c.figure;
        for (const auto& [name, g] : r.regions) {
            const std::string p = "region_" + name;
            v.figures[p + "_impact_rate_per_s"] = g.rate;
            v.figures[p + "_coverage"] = g.coverage;
            v.figures[p + "_time_to_target_s"] = g.time;
        }
        out.variants.push_back(std::move(v));
    }
    return out;
}

SweepCompareResult write_sweep_comparison(const SweepPlan& plan, const std::string& sweep_dir, const std::string& baseline,
                                          const std::string& title) {
    SweepCompareResult result;
    std::size_t base = 0;
    if (!baseline.empty()) {
        base = plan.variants.size();
        for (std::size_t v = 0; v < plan.variants.size(); ++v)
            if (plan.variants[v].name == baseline) base = v;
        if (base == plan.variants.size()) throw std::runtime_error("--baseline '" + baseline + "': no such variant");
    }
    std::vector<std::string> region_names;
    double target = NAN;
    const std::vector<CompareRow> rows = variant_rows(plan, result.component, region_names, target);
    fs::create_directories(sweep_dir);
    const std::string to_target = std::isfinite(target) ? "time to " + fmt(target * 100.0, 4) + " %" : std::string("time to target");

    // comparison.csv: one row per variant.
    const auto& columns = kCompareColumns;
    std::ostringstream csv;
    csv << "variant";
    for (const SweepAxis& a : plan.axes) csv << "," << a.path;
    csv << ",runs_finished,target_coverage";
    for (const CompareColumn& c : columns) csv << "," << c.name << "," << c.name << "_ci95";
    csv << ",slowest_region,why_no_time_to_target,why_no_slowest_region_time,why_no_time_to_target_everywhere";
    for (const CompareColumn& c : columns)
        if (c.compared) csv << ",delta_" << c.name << ",verdict_" << c.name;
    for (const std::string& name : region_names) {
        const std::string p = ",region_" + name;
        csv << p << "_impact_rate_per_s" << p << "_impact_rate_ci95_per_s" << p << "_coverage" << p << "_coverage_ci95" << p
            << "_time_to_target_s" << p << "_time_to_target_ci95_s";
    }
    csv << "\n";
    for (std::size_t v = 0; v < plan.variants.size(); ++v) {
        const CompareRow& r = rows[v];
        csv << plan.variants[v].name;
        for (const SweepAxis& a : plan.axes) csv << ",\"" << sweep_value(plan.variants[v], a.path) << "\"";
        csv << "," << r.runs << "," << csv_cell(std::isfinite(target) ? std::optional<double>(target) : std::nullopt);
        for (const CompareColumn& c : columns) csv << "," << csv_cell((r.*c.figure).mean) << "," << csv_cell((r.*c.figure).ci95);
        csv << "," << r.slowest_region;
        for (const SweepFigure* f : {&r.whole, &r.slowest, &r.everywhere}) csv << ",\"" << f->missing << "\"";
        for (const CompareColumn& c : columns)
            if (c.compared) {
                const SweepDifference d = compare_figures(r.*c.figure, rows[base].*c.figure);
                csv << "," << csv_cell(d.delta) << "," << d.verdict;
            }
        for (const std::string& name : region_names) {
            const auto it = r.regions.find(name);
            const CompareRow::Region g = it != r.regions.end() ? it->second : CompareRow::Region{};
            for (const SweepFigure* f : {&g.rate, &g.coverage, &g.time}) csv << "," << csv_cell(f->mean) << "," << csv_cell(f->ci95);
        }
        csv << "\n";
    }
    write_file_atomically(sweep_dir + "/comparison.csv", csv.str());

    // report.md: what decides first (the slowest region, everywhere, uniformity, the share below
    // the target), then the run's raw figures.
    std::ostringstream md;
    md << "# peensim sweep: " << title << "\n\n";
    md << plan.variants.size() << " variants x " << plan.seeds << (plan.seeds == 1 ? " seed" : " seeds")
       << "; the logged part compared: " << (result.component.empty() ? std::string("(none finished)") : "`" + result.component + "`")
       << "; baseline `" << plan.variants[base].name << "`.\n\n";
    const auto verdict = [&](std::size_t v, SweepFigure CompareRow::*f, double scale) {
        if (v == base) return std::string("baseline");
        const SweepDifference d = compare_figures(rows[v].*f, rows[base].*f);
        return d.delta ? (*d.delta >= 0 ? "+" : "") + fmt(*d.delta * scale, 3) + " (" + d.verdict + ")" : std::string("-");
    };
    const auto timed = [](const SweepFigure& f) { return f.mean ? shown(f) : f.missing.empty() ? std::string("-") : f.missing; };
    md << "## What decides: " << to_target << "\n\n"
       << "| variant | runs | slowest region | its " << to_target << " (s) | vs baseline | " << to_target
       << " everywhere (s) | vs baseline | "
       << "uniformity | vs baseline | share below target (%) | vs baseline | " << to_target << ", whole part (s) | vs baseline |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t v = 0; v < plan.variants.size(); ++v) {
        const CompareRow& r = rows[v];
        md << "| " << plan.variants[v].name << " | " << r.runs << "/" << plan.seeds << " | "
           << (r.slowest_region.empty() ? "-" : r.slowest_region) << " | " << timed(r.slowest) << " | "
           << verdict(v, &CompareRow::slowest, 1.0) << " | " << timed(r.everywhere) << " | " << verdict(v, &CompareRow::everywhere, 1.0)
           << " | " << shown(r.uniformity, 1.0, 3) << " | " << verdict(v, &CompareRow::uniformity, 1.0) << " | "
           << shown(r.share_below, 100.0, 3) << " | " << verdict(v, &CompareRow::share_below, 100.0) << " | " << timed(r.whole) << " | "
           << verdict(v, &CompareRow::whole, 1.0) << " |\n";
    }
    md << "\n## The runs' figures\n\n"
       << "| variant | impacts per s | vs baseline | mean v_n (m/s) | p90 v_n (m/s) | coverage (%) | vs baseline |\n"
       << "|---|---|---|---|---|---|---|\n";
    for (std::size_t v = 0; v < plan.variants.size(); ++v) {
        const CompareRow& r = rows[v];
        md << "| " << plan.variants[v].name << " | " << shown(r.rate) << " | " << verdict(v, &CompareRow::rate, 1.0) << " | "
           << shown(r.mean_vn) << " | " << shown(r.p90_vn) << " | " << shown(r.coverage, 100.0) << " | "
           << verdict(v, &CompareRow::coverage, 100.0) << " |\n";
    }
    md << "\nIntervals are 95 %: "
       << (plan.seeds > 1 ? std::string("Student's t over the seed replicates (process.seed, +1, ...).")
                          : "one seed, so the impact rate's and mean speed's come from the run's " + std::to_string(kFigureBatches) +
                                " time batches (batch means), the times' and the uniformity's from the run's own forecast interval "
                                "(its wider side); coverage, the share below target and p90 have none (give --seeds 2 or more).")
       << " A difference \"differs\" when it exceeds the combined half-width sqrt(a^2 + b^2) of the two intervals. The times are the "
          "report's forecasts from where the dents landed (each run's `analysis/report.md`): the slowest region is the named region "
          "with the latest time in each run (here the one slowest in most runs), \"everywhere\" also counts the part outside the "
          "regions; a variant shows why it has no time (\"too short: run ... s\") when any of its runs has none. Every figure and "
          "its interval, per region too: `comparison.csv`; each run is an ordinary run directory: `<variant>/s<k>/`.\n";

    // A plot per varied field with numeric values: the time to the target everywhere (with its
    // interval) against the value.
    for (std::size_t a = 0; a < plan.axes.size(); ++a) {
        std::ostringstream data;
        int points = 0;
        for (std::size_t v = 0; v < plan.variants.size(); ++v) {
            const double x = leading_number(sweep_value(plan.variants[v], plan.axes[a].path));
            const CompareRow& r = rows[v];
            if (!std::isfinite(x) || !r.everywhere.mean) continue;
            data << x << " " << *r.everywhere.mean << " " << r.everywhere.ci95.value_or(0.0) << "\n";
            ++points;
        }
        if (points == 0) continue;
        std::string key = sweep_variant_name({{plan.axes[a].path, ""}});
        key.pop_back();  // the "-" before the (empty) value
        const std::string stem = "time_to_target_everywhere_vs_" + key;
        std::ostringstream gp;
        gp << "set terminal pngcairo size " << kPlotWidthPx << "," << kPlotHeightPx << "\nset output out\n"
           << "set title " << gnuplot_string(gnuplot_text(title + ": " + to_target + " everywhere")) << "\n"
           << "set xlabel " << gnuplot_string(gnuplot_text(plan.axes[a].path + unit_of(plan.axes[a].values.front()))) << "\nset ylabel "
           << gnuplot_string(gnuplot_text(to_target + " everywhere (s)"))
           << "\nset grid\nset key off\nset offsets graph 0.05, 0.05, 0.05, 0.05\n"
           << "$d << EOD\n"
           << data.str() << "EOD\n"
           << "plot $d using 1:2:3 with yerrorbars pt 7 lc rgb '#1f77b4'\n";
        const std::string note = plot_with_gnuplot(sweep_dir, stem, gp.str());
        if (note.empty()) {
            result.pngs.push_back(sweep_dir + "/" + stem + ".png");
            md << "\n![" << to_target << " everywhere against " << plan.axes[a].path << "](" << stem << ".png)\n";
        } else {
            result.plot_note = note;
        }
    }
    if (!result.plot_note.empty()) md << "\nPlots: " << result.plot_note << ".\n";
    // The variants side by side in 3D: in report.html, which is report.md with its plots inside.
    std::string view_note;
    const std::map<std::string, std::string> views =
        sweep_views(plan, result.component, std::isfinite(target) ? target : kFullCoverage, three_js_library_dir(), view_note);
    md << "\n## The variants in 3D\n\n";
    if (!views.empty())
        md << "report.html shows the variants side by side in one 3D view, on one colour bar per field (coverage with the target "
              "marked, impact density, mean normal speed, region): drag to turn them, click on one to read its values there.\n\n"
           << kSweepViewMarker << "\n";
    else
        md << view_note << "\n";
    write_file_atomically(sweep_dir + "/report.md", md.str());
    write_file_atomically(sweep_dir + "/report.html",
                          markdown_to_html(md.str(), "peensim sweep: " + title, image_files_in(sweep_dir), views));
    return result;
}

}  // namespace peensim
