#include "app/sweep_compare.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "analysis/sample_mean.h"
#include "analysis/student_t.h"
#include "app/analysis_format.h"
#include "app/analysis_plots.h"
#include "app/component_analysis.h"
#include "output/atomic_file.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// What one finished run gives the comparison.
struct RunFigures {
    double rate = NAN, mean_vn = NAN, p90_vn = NAN, coverage = NAN, t98 = NAN, t98_se = NAN, almen = NAN;
    std::vector<double> batch_rate, batch_vn;
    std::map<std::string, std::pair<double, double>> regions;  // name -> (impact rate, coverage)
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
    r.rate = value_or_nan(*c, "impact_rate_per_s");
    r.mean_vn = value_or_nan(*c, "mean_vn_mps");
    r.coverage = value_or_nan(*c, "coverage");
    r.t98 = value_or_nan(*c, "time_to_98_s");
    const double k = value_or_nan(*c, "avrami_k_per_s"), k_se = value_or_nan(*c, "avrami_k_se_per_s");
    r.t98_se = r.t98 * k_se / k;  // t98 = ln 50 / k: its relative error is k's
    r.almen = value_or_nan(*c, "almen_dose_J_per_m2");
    r.batch_rate = numbers(*c, "batch_impact_rate_per_s");
    r.batch_vn = numbers(*c, "batch_mean_vn_mps");
    for (const auto& s : summary.value("normal_speed", nlohmann::json::array()))
        if (s.value("component", "") == component) r.p90_vn = value_or_nan(s, "p90_normal_speed_mps");
    for (const auto& g : c->value("regions", nlohmann::json::array()))
        r.regions[g.value("region", "")] = {value_or_nan(g, "impact_rate_per_s"), value_or_nan(g, "coverage")};
    return r;
}

// A figure over the variant's runs: with two or more, Student's t over the runs; with one,
// `single` (its batch means, or a standard error of its own), or no interval.
SweepFigure figure(const std::vector<RunFigures>& runs, double RunFigures::*member, const SweepFigure& single = {}) {
    std::vector<double> v;
    for (const RunFigures& r : runs) v.push_back(r.*member);
    const SampleMean s = sample_mean(v);
    if (s.count == 0) return {};
    if (runs.size() == 1) return {s.mean, single.ci95};
    return mean_with_ci95(v);
}

std::string cell(const std::optional<double>& x) {
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

}  // namespace

SweepFigure mean_with_ci95(const std::vector<double>& values) {
    const SampleMean s = sample_mean(values);
    if (s.count == 0) return {};
    if (s.count < 2) return {s.mean, std::nullopt};
    return {s.mean, student_t_two_sided_quantile(0.05, static_cast<double>(s.count) - 1.0) * s.standard_error};
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
    // Every finished run, by variant.
    std::vector<std::vector<RunFigures>> runs(plan.variants.size());
    for (const SweepRun& run : plan.runs)
        if (auto r = read_run(run.dir, result.component)) runs[run.variant].push_back(*r);

    struct Row {
        SweepFigure rate, mean_vn, p90_vn, coverage, t98, almen;
        std::map<std::string, std::pair<SweepFigure, SweepFigure>> regions;
        std::size_t runs = 0;
    };
    std::vector<Row> rows(plan.variants.size());
    std::vector<std::string> region_names;
    for (std::size_t v = 0; v < plan.variants.size(); ++v) {
        const std::vector<RunFigures>& rs = runs[v];
        Row& row = rows[v];
        row.runs = rs.size();
        if (rs.empty()) continue;
        row.rate = figure(rs, &RunFigures::rate, mean_with_ci95(rs[0].batch_rate));
        row.mean_vn = figure(rs, &RunFigures::mean_vn, mean_with_ci95(rs[0].batch_vn));
        row.p90_vn = figure(rs, &RunFigures::p90_vn);
        row.coverage = figure(rs, &RunFigures::coverage);
        const double t98_ci = 1.96 * rs[0].t98_se;  // one run: the fit's own (normal) interval
        row.t98 = figure(rs, &RunFigures::t98, SweepFigure{std::nullopt, std::isfinite(t98_ci) ? std::optional<double>(t98_ci) : std::nullopt});
        row.almen = figure(rs, &RunFigures::almen);
        for (const auto& [name, unused] : rs[0].regions) {
            (void)unused;
            if (std::find(region_names.begin(), region_names.end(), name) == region_names.end()) region_names.push_back(name);
            std::vector<double> rate, cov;
            for (const RunFigures& r : rs) {
                const auto it = r.regions.find(name);
                if (it != r.regions.end()) rate.push_back(it->second.first), cov.push_back(it->second.second);
            }
            row.regions[name] = {mean_with_ci95(rate), mean_with_ci95(cov)};
        }
    }
    fs::create_directories(sweep_dir);

    // comparison.csv: one row per variant.
    std::ostringstream csv;
    csv << "variant";
    for (const SweepAxis& a : plan.axes) csv << "," << a.path;
    const char* figures[] = {"impact_rate_per_s", "mean_vn_mps", "p90_vn_mps", "coverage", "time_to_98_s", "almen_dose_J_per_m2"};
    csv << ",runs_finished";
    for (const char* f : figures) csv << "," << f << "," << f << "_ci95";
    for (const char* f : {"impact_rate_per_s", "coverage", "time_to_98_s"}) csv << ",delta_" << f << ",verdict_" << f;
    for (const std::string& name : region_names)
        csv << ",region_" << name << "_impact_rate_per_s,region_" << name << "_impact_rate_ci95_per_s,region_" << name << "_coverage,region_" << name
            << "_coverage_ci95";
    csv << "\n";
    for (std::size_t v = 0; v < plan.variants.size(); ++v) {
        const Row& r = rows[v];
        csv << plan.variants[v].name;
        for (const SweepAxis& a : plan.axes) csv << ",\"" << sweep_value(plan.variants[v], a.path) << "\"";
        csv << "," << r.runs;
        for (const SweepFigure* f : {&r.rate, &r.mean_vn, &r.p90_vn, &r.coverage, &r.t98, &r.almen}) csv << "," << cell(f->mean) << "," << cell(f->ci95);
        for (const auto& [mine, theirs] : {std::pair{&r.rate, &rows[base].rate}, std::pair{&r.coverage, &rows[base].coverage},
                                           std::pair{&r.t98, &rows[base].t98}}) {
            const SweepDifference d = compare_figures(*mine, *theirs);
            csv << "," << cell(d.delta) << "," << d.verdict;
        }
        for (const std::string& name : region_names) {
            const auto it = r.regions.find(name);
            const SweepFigure rate = it != r.regions.end() ? it->second.first : SweepFigure{};
            const SweepFigure cov = it != r.regions.end() ? it->second.second : SweepFigure{};
            csv << "," << cell(rate.mean) << "," << cell(rate.ci95) << "," << cell(cov.mean) << "," << cell(cov.ci95);
        }
        csv << "\n";
    }
    write_file_atomically(sweep_dir + "/comparison.csv", csv.str());

    // report.md.
    std::ostringstream md;
    md << "# peensim sweep: " << title << "\n\n";
    md << plan.variants.size() << " variants x " << plan.seeds << (plan.seeds == 1 ? " seed" : " seeds") << "; the logged part compared: "
       << (result.component.empty() ? std::string("(none finished)") : "`" + result.component + "`") << "; baseline `"
       << plan.variants[base].name << "`.\n\n";
    md << "| variant | runs | impacts per s | mean v_n (m/s) | p90 v_n (m/s) | coverage (%) | time to 98 % (s) | vs baseline: time to 98 % | coverage | impacts per s |\n"
       << "|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t v = 0; v < plan.variants.size(); ++v) {
        const Row& r = rows[v];
        const auto verdict = [&](const SweepFigure& mine, const SweepFigure& theirs, double scale) {
            if (v == base) return std::string("baseline");
            const SweepDifference d = compare_figures(mine, theirs);
            return d.delta ? (*d.delta >= 0 ? "+" : "") + fmt(*d.delta * scale, 3) + " (" + d.verdict + ")" : std::string("-");
        };
        md << "| " << plan.variants[v].name << " | " << r.runs << "/" << plan.seeds << " | " << shown(r.rate) << " | " << shown(r.mean_vn) << " | "
           << shown(r.p90_vn) << " | " << shown(r.coverage, 100.0) << " | " << shown(r.t98) << " | " << verdict(r.t98, rows[base].t98, 1.0) << " | "
           << verdict(r.coverage, rows[base].coverage, 100.0) << " | " << verdict(r.rate, rows[base].rate, 1.0) << " |\n";
    }
    md << "\nIntervals are 95 %: " << (plan.seeds > 1
                                           ? "Student's t over the seed replicates (process.seed, +1, ...)."
                                           : "one seed, so the impact rate's and mean speed's come from the run's " + std::to_string(kFigureBatches) +
                                                 " time batches (batch means), the time to 98 %'s from the coverage fit's standard error; "
                                                 "coverage and p90 have none (give --seeds 2 or more).")
       << " A difference \"differs\" when it exceeds the combined half-width sqrt(a^2 + b^2) of the two intervals. The time to 98 % "
          "is the Avrami fit's (extrapolated when the run is shorter). Every figure and its interval, per region too: `comparison.csv`; "
          "each run is an ordinary run directory: `<variant>/s<k>/`.\n";

    // A plot per varied field with numeric values: time to 98 % (with its interval) against the value.
    for (std::size_t a = 0; a < plan.axes.size(); ++a) {
        std::ostringstream data;
        int points = 0;
        for (std::size_t v = 0; v < plan.variants.size(); ++v) {
            const double x = leading_number(sweep_value(plan.variants[v], plan.axes[a].path));
            const Row& r = rows[v];
            if (!std::isfinite(x) || !r.t98.mean) continue;
            data << x << " " << *r.t98.mean << " " << r.t98.ci95.value_or(0.0) << "\n";
            ++points;
        }
        if (points == 0) continue;
        std::string key = sweep_variant_name({{plan.axes[a].path, ""}});
        key.pop_back();  // the "-" before the (empty) value
        const std::string stem = "time_to_98_vs_" + key;
        std::ostringstream gp;
        gp << "set terminal pngcairo size " << kPlotWidthPx << "," << kPlotHeightPx << "\nset output out\n"
           << "set title " << gnuplot_string(gnuplot_text(title + ": time to 98 % coverage")) << "\n"
           << "set xlabel " << gnuplot_string(gnuplot_text(plan.axes[a].path + unit_of(plan.axes[a].values.front())))
           << "\nset ylabel 'time to 98 % (s)'\nset grid\nset key off\nset offsets graph 0.05, 0.05, 0.05, 0.05\n"
           << "$d << EOD\n" << data.str() << "EOD\n"
           << "plot $d using 1:2:3 with yerrorbars pt 7 lc rgb '#1f77b4'\n";
        const std::string note = plot_with_gnuplot(sweep_dir, stem, gp.str());
        if (note.empty()) {
            result.pngs.push_back(sweep_dir + "/" + stem + ".png");
            md << "\n![time to 98 % against " << plan.axes[a].path << "](" << stem << ".png)\n";
        } else {
            result.plot_note = note;
        }
    }
    if (!result.plot_note.empty()) md << "\nPlots: " << result.plot_note << ".\n";
    write_file_atomically(sweep_dir + "/report.md", md.str());
    return result;
}

}  // namespace peensim
