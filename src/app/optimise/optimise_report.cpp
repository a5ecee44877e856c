#include "app/optimise/optimise_report.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/analysis/analysis_format.h"
#include "app/analysis/analysis_plots.h"
#include "app/analysis/report_views.h"
#include "app/component_analysis.h"
#include "app/sweep/sweep_views.h"
#include "output/atomic_file.h"
#include "output/markdown_html.h"

namespace peensim {

namespace {

// The model's value of the objective at u: its mean and 95 % interval, as the figure.
struct ModelPrediction {
    double mean = NAN, low = NAN, high = NAN;
    double half_width() const { return 0.5 * (high - low); }
};

ModelPrediction model_prediction(const OptimiseResult& r, const Eigen::VectorXd& u) {
    const ObjectiveScale scale = ObjectiveScale::of(r.study);
    const GpPrediction p = r.model->objective(u);
    const double sd = std::sqrt(p.variance);
    const double a = scale.to_figure(p.mean - 1.96 * sd), b = scale.to_figure(p.mean + 1.96 * sd);
    return {scale.to_figure(p.mean), std::min(a, b), std::max(a, b)};
}

std::string figure_shown(const SweepFigure& f, int digits = 4) {
    if (!f.mean) return f.missing.empty() ? std::string("-") : f.missing;
    return fmt(*f.mean, digits) + (f.ci95 ? " +- " + fmt(*f.ci95, 2) : "");
}

std::string evaluation_cell(const std::optional<double>& x) {
    if (!x || !std::isfinite(*x)) return "";
    std::ostringstream s;
    s.precision(7);
    s << *x;
    return s.str();
}

// The variable's column name in evaluations.csv: its name and unit ("speed_rpm").
std::string variable_column(const StudyVariable& v) {
    std::string unit;
    for (const char c : v.unit) unit += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return unit.empty() ? v.name : v.name + "_" + unit;
}

std::string value_figure_shown(const StudyVariable& v, const std::optional<double>& x) {
    return x ? study_value_text(v, *x) : std::string("(the scene's)");
}

nlohmann::ordered_json json_figure(const SweepFigure& f) {
    nlohmann::ordered_json j;
    j["mean"] = f.mean && std::isfinite(*f.mean) ? nlohmann::ordered_json(*f.mean) : nlohmann::ordered_json(nullptr);
    j["ci95"] = f.ci95 && std::isfinite(*f.ci95) ? nlohmann::ordered_json(*f.ci95) : nlohmann::ordered_json(nullptr);
    if (!f.missing.empty()) j["why_none"] = f.missing;
    return j;
}

// The command that runs the winner again: its first run, byte for byte.
std::string reproduce_command(const OptimiseResult& r, const SweepPlan& plan) {
    std::ostringstream c;
    c << "peensim run " << r.study.scene_path << " -o out/" << r.settings[r.best].name << "-again";
    for (const SweepRun& run : plan.runs)
        if (run.variant == r.best && run.replicate == 0)
            for (const std::string& o : run.overrides) c << " --set \"" << o << "\"";
    return c.str();
}

}  // namespace

OptimiseReportFiles write_optimise_report(const OptimiseResult& r, const std::string& dir) {
    OptimiseReportFiles files;
    const Study& study = r.study;
    const ObjectiveScale scale = ObjectiveScale::of(study);
    const std::string goal = study.maximise ? "maximise" : "minimise";
    const std::size_t n = r.settings.size();
    const StudySetting& best = r.settings[r.best];
    const bool modelled = r.model.has_value() && !r.points.empty() && complete(best);
    std::vector<double> p_feasible(n, NAN);
    std::vector<ModelPrediction> predicted(n);
    if (r.model)
        for (std::size_t k = 0; k < n; ++k)
            if (complete(r.settings[k])) {
                const Eigen::VectorXd u = unit_point(study, r.settings[k]);
                predicted[k] = model_prediction(r, u);
                p_feasible[k] = r.model->probability_feasible(u);
            }
    int runs_used = 0;
    for (const StudySetting& s : r.settings) runs_used += s.seeds;

    // evaluations.csv: a row per setting.
    // Whether a setting's own runs meet every constraint (on their mean; a figure not measured counts as met).
    const auto measured_holds = [&](std::size_t k) {
        for (const StudyConstraint& c : study.constraints) {
            const SweepFigure g = r.figures.at(k, c.component, c.figure);
            if (g.mean && (c.is_max ? *g.mean > c.limit : *g.mean < c.limit)) return false;
        }
        return true;
    };
    // The constraints' figures, each once (a window is two constraints on one figure).
    std::vector<std::pair<std::string, std::string>> constraint_figures;  // (component, figure)
    for (const StudyConstraint& c : study.constraints)
        if (std::find(constraint_figures.begin(), constraint_figures.end(), std::make_pair(c.component, c.figure)) ==
            constraint_figures.end())
            constraint_figures.emplace_back(c.component, c.figure);

    std::ostringstream csv;
    csv << "setting,round,why";
    for (const StudyVariable& v : study.variables) csv << "," << variable_column(v);
    csv << ",runs,runs_finished," << study.objective << "," << study.objective << "_ci95,predicted_" << study.objective << ",predicted_"
        << study.objective << "_low,predicted_" << study.objective << "_high";
    for (const auto& [component, figure] : constraint_figures) {
        const std::string name = component.empty() ? figure : component + "_" + figure;
        csv << "," << name << "," << name << "_ci95";
    }
    csv << ",constraints_met,probability_feasible,why_no_value\n";
    for (std::size_t k = 0; k < n; ++k) {
        const StudySetting& s = r.settings[k];
        const SweepFigure o = r.figures.at(k, study.objective_component, study.objective);
        csv << s.name << "," << s.round << "," << s.why;
        for (const auto& x : s.values) csv << "," << evaluation_cell(x);
        csv << "," << s.seeds << "," << r.figures.runs(k) << "," << evaluation_cell(o.mean) << "," << evaluation_cell(o.ci95) << ","
            << evaluation_cell(predicted[k].mean) << "," << evaluation_cell(predicted[k].low) << "," << evaluation_cell(predicted[k].high);
        for (const auto& [component, figure] : constraint_figures) {
            const SweepFigure g = r.figures.at(k, component, figure);
            csv << "," << evaluation_cell(g.mean) << "," << evaluation_cell(g.ci95);
        }
        csv << "," << (measured_holds(k) ? "yes" : "no") << "," << evaluation_cell(p_feasible[k]) << ",\""
            << (o.missing.empty() && !o.mean ? std::string("the runs give no value") : o.missing) << "\"\n";
    }
    write_file_atomically(dir + "/evaluations.csv", csv.str());

    // The answer.
    std::ostringstream md, summary;
    md << "# peensim optimise: " << r.title << "\n\n"
       << "Study `" << study.path << "`: " << goal << " `" << study.objective << "`";
    for (const StudyConstraint& c : study.constraints)
        md << (&c == &study.constraints.front() ? " with " : ", ") << "`" << c.figure << "` " << (c.is_max ? "<= " : ">= ")
           << fmt(c.limit, 6);
    md << " over " << study.variables.size() << (study.variables.size() == 1 ? " variable" : " variables") << "; " << n << " settings, "
       << runs_used << " runs of the search (budget " << r.budget << "), stopped because " << r.stopped_because << ".\n\n";
    md << "## The winner: `" << best.name << "`\n\n| variable | start | winner | searched |\n|---|---|---|---|\n";
    for (std::size_t i = 0; i < study.variables.size(); ++i) {
        const StudyVariable& v = study.variables[i];
        md << "| " << v.name << " | " << value_figure_shown(v, r.settings[0].values[i]) << " | " << value_figure_shown(v, best.values[i])
           << " | " << study_value_text(v, v.min) << " to " << study_value_text(v, v.max) << (v.log_scale ? ", log scale" : "")
           << (v.integer ? ", whole" : "") << " |\n";
        summary << "  " << v.name << " = " << value_figure_shown(v, best.values[i]) << " (start "
                << value_figure_shown(v, r.settings[0].values[i]) << ")\n";
    }
    // winner.json: the answer for programs (the Python API's Optimisation.winner).
    nlohmann::ordered_json winner;
    winner["setting"] = best.name;
    winner["objective"] = study.objective;
    winner["goal"] = goal;
    winner["values"] = nlohmann::ordered_json::object();
    for (std::size_t i = 0; i < study.variables.size(); ++i)
        winner["values"][study.variables[i].name] = best.values[i]
                                                        ? nlohmann::ordered_json(study_value_text(study.variables[i], *best.values[i]))
                                                        : nlohmann::ordered_json(nullptr);
    winner["set"] = nlohmann::ordered_json::array();
    for (const auto& [path, value] : setting_overrides(study, best)) winner["set"].push_back(path + "=" + value);
    const SweepFigure measured_best = r.figures.at(r.best, study.objective_component, study.objective);
    md << "\n| `" << study.objective << "` | value | 95 % interval | from |\n|---|---|---|---|\n";
    if (modelled)
        winner["predicted"] = {{"mean", predicted[r.best].mean}, {"low", predicted[r.best].low}, {"high", predicted[r.best].high}};
    winner["search_runs"] = json_figure(r.figures.at(r.best, study.objective_component, study.objective));
    if (modelled) {
        const ModelPrediction& p = predicted[r.best];
        md << "| winner, predicted | " << fmt(p.mean, 6) << " | " << fmt(p.low, 6) << " to " << fmt(p.high, 6) << " | the model over all "
           << r.points.size() << " settings |\n";
        summary << "  " << study.objective << ": predicted " << fmt(p.mean, 6) << " [" << fmt(p.low, 6) << ", " << fmt(p.high, 6) << "]";
    }
    md << "| winner, its search runs | " << figure_shown(measured_best) << " | | " << best.seeds << (best.seeds == 1 ? " run" : " runs")
       << " |\n";
    const SweepFigure measured_start = r.figures.at(0, study.objective_component, study.objective);
    md << "| start, its search runs | " << figure_shown(measured_start) << " | | " << r.settings[0].seeds
       << (r.settings[0].seeds == 1 ? " run" : " runs") << " |\n";
    if (r.confirmed) {
        const SweepFigure cs = r.confirmed->at(0, study.objective_component, study.objective);
        const SweepFigure cb = r.best == 0 ? cs : r.confirmed->at(1, study.objective_component, study.objective);
        const std::size_t confirm_runs = r.confirmed->runs(0);
        winner["confirmed"] = json_figure(cb);
        winner["start_confirmed"] = json_figure(cs);
        md << "| winner, confirmed | " << figure_shown(cb) << " | | " << confirm_runs << " new runs (seeds never used in the search) |\n"
           << "| start, confirmed | " << figure_shown(cs) << " | | " << confirm_runs << " new runs |\n\n";
        summary << "; confirmed " << figure_shown(cb) << " (" << confirm_runs << " new runs)\n  start, confirmed: " << figure_shown(cs)
                << "\n";
        // The constraints the start breaks (its confirmed means): then it is no rival.
        std::string start_breaks;
        for (const StudyConstraint& c : study.constraints) {
            const SweepFigure g = r.confirmed->at(0, c.component, c.figure);
            if (g.mean && (c.is_max ? *g.mean > c.limit : *g.mean < c.limit))
                start_breaks += (start_breaks.empty() ? "`" : ", `") + c.figure + (c.is_max ? "` <= " : "` >= ") + fmt(c.limit, 6);
        }
        if (r.best == 0) {
            md << "The start is the winner: no setting searched did better.\n";
        } else {
            const SweepDifference d = compare_figures(cb, cs);
            if (d.delta && cs.mean) {
                const double better = study.maximise ? *d.delta : -*d.delta;
                md << "**Against the start:** " << (better >= 0 ? "better by " : "worse by ") << fmt(std::abs(*d.delta)) << " ("
                   << fmt(100.0 * std::abs(*d.delta) / std::abs(*cs.mean), 3) << " %), " << d.verdict
                   << " (the difference against the two confirmed intervals combined)"
                   << (start_breaks.empty() ? std::string() : "; but the start breaks " + start_breaks + ", the winner does not") << ".\n";
                summary << "  against the start: " << (better >= 0 ? "better by " : "worse by ")
                        << fmt(100.0 * std::abs(*d.delta) / std::abs(*cs.mean), 3) << " % (" << d.verdict << ")\n";
                // The verdict a sign-off reads first: what the confirmation runs can and cannot say.
                std::string verdict;
                if (!start_breaks.empty())
                    verdict =
                        "the winner meets the constraints the start breaks (" + start_breaks + ")" +
                        (d.verdict == "differs" ? std::string(better >= 0 ? ", and is better too." : ", at this cost in the objective.")
                                                : ", at no cost in the objective the confirmation runs can see.");
                else if (d.verdict == "differs" && better >= 0)
                    verdict = "the winner is better than the start, confirmed by runs the search never saw.";
                else if (d.verdict == "differs")
                    verdict =
                        "the confirmation runs find the winner worse than the start: keep the start (the model was misled; more "
                        "`seeds` or longer runs give it less noise to be misled by).";
                else
                    verdict = "the confirmation runs cannot tell the winner from the start (their 95 % intervals: +- " +
                              fmt(100.0 * cb.ci95.value_or(NAN) / std::abs(*cb.mean), 2) + " % and +- " +
                              fmt(100.0 * cs.ci95.value_or(NAN) / std::abs(*cs.mean), 2) +
                              " %): within these bounds the variables move the objective less than that. More `confirm` runs narrow "
                              "it.";
                md << "\n**Verdict:** " << verdict << "\n";
                summary << "  verdict: " << verdict << "\n";
                winner["verdict"] = verdict;
            }
        }
        if (modelled && cb.mean) {
            const ModelPrediction& p = predicted[r.best];
            const double gap = std::abs(*cb.mean - p.mean), allowed = std::hypot(cb.ci95.value_or(0.0), p.half_width());
            md << "\n**The winner's prediction " << (gap <= allowed ? "holds" : "does not hold") << ":** the confirmed " << fmt(*cb.mean)
               << " is " << fmt(gap) << " from the predicted " << fmt(p.mean) << " against their intervals combined, " << fmt(allowed)
               << ".\n";
            winner["prediction_holds"] = gap <= allowed;
            summary << "  the winner's prediction " << (gap <= allowed ? "holds" : "does not hold") << " (" << fmt(gap) << " off, allowed "
                    << fmt(allowed) << ")\n";
        }
        // The predicted improvement over the start (the model's difference, with the covariance of
        // the two predictions) against the confirmed one.
        if (modelled && r.best != 0 && complete(r.settings[0]) && cb.mean && cs.mean) {
            const Eigen::VectorXd ub = unit_point(study, best), us = unit_point(study, r.settings[0]);
            const GaussianProcess& gp = r.model->objective_model();
            const GpPrediction pb = gp.predict(ub), ps = gp.predict(us);
            const double fb = scale.to_figure(pb.mean), fs = scale.to_figure(ps.mean);
            const double gb = scale.log ? scale.sign * fb : scale.sign,
                         gs = scale.log ? scale.sign * fs : scale.sign;  // d figure / d model
            const double var = std::max(0.0, gb * gb * pb.variance + gs * gs * ps.variance - 2.0 * gb * gs * gp.covariance(ub, us));
            const double predicted_change = fb - fs, predicted_half = 1.96 * std::sqrt(var);
            const double confirmed_change = *cb.mean - *cs.mean, confirmed_half = std::hypot(cb.ci95.value_or(0.0), cs.ci95.value_or(0.0));
            const bool holds = std::abs(confirmed_change - predicted_change) <= std::hypot(predicted_half, confirmed_half);
            winner["change_from_start"] = {{"predicted", predicted_change},
                                           {"predicted_ci95", predicted_half},
                                           {"confirmed", confirmed_change},
                                           {"confirmed_ci95", confirmed_half},
                                           {"holds", holds}};
            md << "\n**The predicted improvement " << (holds ? "holds" : "does not hold") << ":** the model predicted the winner "
               << fmt(predicted_change) << " +- " << fmt(predicted_half, 3) << " from the start (" << fmt(100.0 * predicted_change / fs, 3)
               << " %); the confirmation runs measured " << fmt(confirmed_change) << " +- " << fmt(confirmed_half, 3) << " ("
               << fmt(100.0 * confirmed_change / *cs.mean, 3) << " %).\n";
            summary << "  predicted change from the start " << fmt(predicted_change) << " +- " << fmt(predicted_half, 3) << ", confirmed "
                    << fmt(confirmed_change) << " +- " << fmt(confirmed_half, 3) << ": " << (holds ? "holds" : "does not hold") << "\n";
        }
    } else {
        md << "\nNo confirmation runs (`confirm: 0`).\n";
        if (modelled) summary << "\n";  // the predicted line's end, which a confirmation would have written
    }
    md << "\nThe model's intervals are of what runs of this length give, from seed to seed. The times are forecasts: what a run "
          "carried on to the target would measure has its own interval besides, which each run's analysis gives (a setting's one "
          "run above shows it: its `analysis/report.md`, \"How long to peen\").\n";
    // The constraints at the winner and at the start: measured in the search, confirmed, and the
    // model's probability that they hold. A start that breaks one is no rival, whatever its time.
    if (!study.constraints.empty()) {
        md << "\n| constraint | winner, search runs | winner, confirmed | start, search runs | start, confirmed |\n|---|---|---|---|---|\n";
        const auto holds = [](const StudyConstraint& c, const SweepFigure& g) {
            if (!g.mean) return std::string();
            return std::string((c.is_max ? *g.mean <= c.limit : *g.mean >= c.limit) ? " (holds)" : " (**broken**)");
        };
        for (const StudyConstraint& c : study.constraints) {
            const SweepFigure wb = r.figures.at(r.best, c.component, c.figure), sb = r.figures.at(0, c.component, c.figure);
            SweepFigure wc, sc;
            if (r.confirmed) {
                sc = r.confirmed->at(0, c.component, c.figure);
                wc = r.best == 0 ? sc : r.confirmed->at(1, c.component, c.figure);
            }
            md << "| `" << c.figure << "` " << (c.is_max ? "<= " : ">= ") << fmt(c.limit, 6) << " | " << figure_shown(wb) << holds(c, wb)
               << " | " << figure_shown(wc) << holds(c, wc) << " | " << figure_shown(sb) << holds(c, sb) << " | " << figure_shown(sc)
               << holds(c, sc) << " |\n";
            summary << "  " << c.figure << (c.is_max ? " <= " : " >= ") << fmt(c.limit, 6) << ": winner " << figure_shown(wc.mean ? wc : wb)
                    << holds(c, wc.mean ? wc : wb) << ", start " << figure_shown(sc.mean ? sc : sb) << holds(c, sc.mean ? sc : sb) << "\n";
        }
        md << "\nThe model gives the winner's constraints together a probability of " << fmt(p_feasible[r.best], 3)
           << " to hold (a winner must reach " << fmt(SearchModel::kWinnerConfidence, 3)
           << " if any setting does). A start that breaks a constraint is no rival to the winner, however fast it is.\n";
    }
    md << "\n**To run the winner again** (its first search run, byte for byte):\n\n    "
       << reproduce_command(r, settings_plan(study, r.settings, r.base_seed, "")) << "\n";

    // A plot per variable: the model along it through the winner, and the runs.
    md << "\n## The trade-offs\n\nEach plot: the model's `" << study.objective << "` along one variable, the others at the winner's values "
       << "(line, with its 95 % band), and every setting's own runs (points, their 95 % interval; they differ in the other "
          "variables too, so they scatter about the line; hollow orange where they broke a constraint, and the dashed green line, "
          "right axis, the model's probability that every constraint holds along the line). The winner is circled.\n";
    std::string plot_note;
    if (modelled)
        for (std::size_t i = 0; i < study.variables.size(); ++i) {
            const StudyVariable& v = study.variables[i];
            std::ostringstream band, kept, broke;
            Eigen::VectorXd u = unit_point(study, best);
            for (int k = 0; k <= 100; ++k) {
                u(static_cast<Eigen::Index>(i)) = k / 100.0;
                const double x = v.log_scale ? v.min * std::pow(v.max / v.min, k / 100.0) : v.min + (v.max - v.min) * k / 100.0;
                const ModelPrediction p = model_prediction(r, u);
                band << x << " " << p.low << " " << p.high << " " << p.mean << " " << r.model->probability_feasible(u) << "\n";
            }
            for (std::size_t k = 0; k < n; ++k) {
                const SweepFigure o = r.figures.at(k, study.objective_component, study.objective);
                if (!r.settings[k].values[i] || !o.mean) continue;
                (measured_holds(k) ? kept : broke) << *r.settings[k].values[i] << " " << *o.mean << " " << o.ci95.value_or(0.0) << "\n";
            }
            const SweepFigure o = measured_best;
            const bool constrained = !study.constraints.empty();
            std::ostringstream gp;
            gp << "set terminal pngcairo size " << kPlotWidthPx << "," << kPlotHeightPx << "\nset output out\n"
               << "set title " << gnuplot_string(gnuplot_text(r.title + ": " + study.objective + " against " + v.name)) << "\n"
               << "set xlabel " << gnuplot_string(gnuplot_text(v.name + (v.unit.empty() ? "" : " (" + v.unit + ")"))) << "\n"
               << "set ylabel " << gnuplot_string(gnuplot_text(study.objective)) << "\nset grid\nset key below\n"
               << "set xrange [" << v.min << ":" << v.max << "]\n"
               << (v.log_scale ? "set logscale x\n" : "")
               << (constrained ? "set y2range [0:1]\nset y2tics\nset y2label 'probability the constraints hold (model)'\n" : "")
               << "$band << EOD\n"
               << band.str() << "EOD\n$kept << EOD\n"
               << kept.str() << "EOD\n$broke << EOD\n"
               << broke.str() << "EOD\n"
               << "plot $band using 1:2:3 with filledcurves fc rgb '#cfe2f3' title 'model, 95 %', $band using 1:4 with lines lw 2 lc rgb "
                  "'#1f77b4' title 'model'";
            if (!kept.str().empty())
                gp << ", $kept using 1:2:3 with yerrorbars pt 7 lc rgb '#444444' title '"
                   << (constrained ? "runs, constraints held" : "runs") << "'";
            if (!broke.str().empty()) gp << ", $broke using 1:2:3 with yerrorbars pt 6 lc rgb '#ff7f0e' title 'runs, a constraint broken'";
            if (constrained) gp << ", $band using 1:5 axes x1y2 with lines dt 2 lw 2 lc rgb '#2ca02c' title 'P(constraints hold)'";
            if (o.mean)
                gp << ", '-' using 1:2 with points pt 6 ps 3 lw 2 lc rgb '#d62728' title 'winner'\n"
                   << *best.values[i] << " " << *o.mean << "\ne\n";
            else
                gp << "\n";
            const std::string stem = "objective_vs_" + variable_column(v);
            const std::string note = plot_with_gnuplot(dir, stem, gp.str());
            if (note.empty()) {
                files.plots = true;
                md << "\n![" << study.objective << " against " << v.name << "](" << stem << ".png)\n";
            } else {
                plot_note = note;
            }
        }
    // The search's progress: each setting's value in the order run, and the best so far.
    {
        std::ostringstream pts, broke, best_so_far;
        double running = NAN;
        for (std::size_t k = 0; k < n; ++k) {
            const SweepFigure o = r.figures.at(k, study.objective_component, study.objective);
            if (!o.mean) continue;
            const bool holds = measured_holds(k);  // a setting that broke a constraint is no "best"
            (holds ? pts : broke) << k << " " << *o.mean << " " << o.ci95.value_or(0.0) << "\n";
            if (holds && (!std::isfinite(running) || (study.maximise ? *o.mean > running : *o.mean < running))) running = *o.mean;
            if (std::isfinite(running)) best_so_far << k << " " << running << "\n";
        }
        if (!pts.str().empty() || !broke.str().empty()) {
            std::ostringstream gp;
            gp << "set terminal pngcairo size " << kPlotWidthPx << "," << kPlotHeightPx << "\nset output out\n"
               << "set title " << gnuplot_string(gnuplot_text(r.title + ": the search")) << "\n"
               << "set xlabel 'setting (in the order run; 0 = the start)'\nset ylabel " << gnuplot_string(gnuplot_text(study.objective))
               << "\nset grid\nset key below\n$pts << EOD\n"
               << pts.str() << "EOD\n$broke << EOD\n"
               << broke.str() << "EOD\n$best << EOD\n"
               << best_so_far.str() << "EOD\nplot 1/0 notitle";
            if (!pts.str().empty())
                gp << ", $pts using 1:2:3 with yerrorbars pt 7 lc rgb '#444444' title '"
                   << (study.constraints.empty() ? "each setting" : "each setting, constraints met") << "'";
            if (!broke.str().empty()) gp << ", $broke using 1:2:3 with yerrorbars pt 6 lc rgb '#ff7f0e' title 'a constraint broken'";
            if (!best_so_far.str().empty()) gp << ", $best using 1:2 with steps lw 2 lc rgb '#d62728' title 'best measured so far'";
            gp << "\n";
            const std::string note = plot_with_gnuplot(dir, "search_progress", gp.str());
            if (note.empty()) {
                files.plots = true;
                md << "\n![the search's progress](search_progress.png)\n";
            } else {
                plot_note = note;
            }
        }
    }
    if (!plot_note.empty()) md << "\nPlots: " << plot_note << ".\n";

    // Every evaluation.
    md << "\n## Every setting\n\n| setting | round | why |";
    for (const StudyVariable& v : study.variables) md << " " << v.name << " |";
    md << " runs | `" << study.objective << "` | predicted (95 %) |";
    for (const StudyConstraint& c : study.constraints) md << " `" << c.figure << "` |";
    md << "\n|---|---|---|";
    for (std::size_t i = 0; i < study.variables.size() + 3 + study.constraints.size(); ++i) md << "---|";
    md << "\n";
    for (std::size_t k = 0; k < n; ++k) {
        const StudySetting& s = r.settings[k];
        md << "| " << (k == r.best ? "**" + s.name + "**" : s.name) << " | " << s.round << " | " << s.why << " |";
        for (std::size_t i = 0; i < study.variables.size(); ++i) md << " " << value_figure_shown(study.variables[i], s.values[i]) << " |";
        md << " " << r.figures.runs(k) << "/" << s.seeds << " | "
           << figure_shown(r.figures.at(k, study.objective_component, study.objective)) << " | "
           << (std::isfinite(predicted[k].mean)
                   ? fmt(predicted[k].mean, 6) + " (" + fmt(predicted[k].low, 6) + " to " + fmt(predicted[k].high, 6) + ")"
                   : "-")
           << " |";
        for (const StudyConstraint& c : study.constraints) md << " " << figure_shown(r.figures.at(k, c.component, c.figure)) << " |";
        md << "\n";
    }
    md << "\nHow it searched: Bayesian optimisation. A Gaussian-process model (Matern 5/2, a length scale per variable, the spread "
          "between seeds fitted with the rest, a setting's noise that spread divided by its runs; "
       << (scale.log ? "the time on a log scale" : "the figure as it is")
       << ") is fitted to every setting run; each round runs the settings of highest expected improvement over the model's best "
          "setting"
       << (study.constraints.empty() ? "" : ", times the model's probability that every constraint holds")
       << ", several at once (each next one chosen as if the earlier had measured the model's mean). The winner is the run setting "
          "with the best predicted value; while the model's 95 % interval there is wider than "
       << fmt(100.0 * study.tolerance, 3)
       << " % of its value, a round gives it one more seed. A setting without a value (a run too short to forecast, or failed) "
          "counts as the worst measured. Intervals are 95 %; a setting's own: Student's t over its seeds, or with one seed the "
          "run's own forecast interval (which also counts the forecast's extrapolation, so it is wider than the spread between seeds "
          "the model fits). Each setting is an ordinary run directory, `"
       << "<setting>/s<k>/`, the confirmation runs `confirm-start/` and `confirm-<winner>/`; every figure: `evaluations.csv`.\n";
    if (r.failed_runs > 0)
        md << "\n"
           << r.failed_runs << (r.failed_runs == 1 ? " run" : " runs")
           << " failed (twice, or once refusing their input): their logs are in `optimise/logs/`.\n";

    // The start and the winner side by side in 3D.
    std::map<std::string, std::string> views;
    if (r.confirm_plan) {
        std::string note;
        views = sweep_views(*r.confirm_plan, r.figures.part().component,
                            std::isfinite(r.figures.part().target_coverage) ? r.figures.part().target_coverage : kFullCoverage,
                            three_js_library_dir(), note);
        md << "\n## The start and the winner in 3D\n\n";
        if (!views.empty())
            md << "report.html shows the start (left) and the winner (right) side by side, each the mean of its confirmation runs, on "
                  "one colour bar per field: drag to turn them, click on one to read its values there.\n\n"
               << kSweepViewMarker << "\n";
        else
            md << note << "\n";
    }
    write_file_atomically(dir + "/report.md", md.str());
    write_file_atomically(dir + "/report.html", markdown_to_html(md.str(), "peensim optimise: " + r.title, image_files_in(dir), views));
    winner["probability_constraints_hold"] =
        std::isfinite(p_feasible[r.best]) ? nlohmann::ordered_json(p_feasible[r.best]) : nlohmann::ordered_json(nullptr);
    write_file_atomically(dir + "/winner.json", winner.dump(1) + "\n");
    files.summary = summary.str();
    return files;
}

}  // namespace peensim
