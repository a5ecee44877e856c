#include "app/optimise/optimise_job.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "analysis/student_t.h"
#include "app/analysis/analysis_format.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/mpi_launch.h"
#include "app/optimise/bayes_search.h"
#include "app/optimise/optimise_report.h"
#include "app/optimise/optimise_settings.h"
#include "app/optimise/study_file.h"
#include "app/report_errors.h"
#include "app/sweep/sweep_book.h"
#include "app/sweep/sweep_checks.h"
#include "app/sweep/sweep_compare.h"
#include "app/sweep/sweep_mpi.h"
#include "app/sweep/sweep_runner.h"
#include "common/input_error.h"
#include "output/atomic_file.h"
#include "scene/resolved_writer.h"
#include "scene/scene_parser.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// The confirmation's seeds start this far past the scene's: never a seed the search ran.
constexpr std::uint64_t kConfirmSeedOffset = 1000;

std::string whole_file(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string setting_name(std::size_t k) {
    char name[16];
    std::snprintf(name, sizeof name, "e%03zu", k);
    return name;
}

// Reads the study and the scene as every run reads them, and reads the scene at the start and at
// each variable's bounds (the others at the start): a path, a unit or a bound the scene refuses is
// an input error before anything runs, blamed on the variable's line.
void check_study(const Study& study, std::ostream& out) {
    std::vector<SweepVariant> variants;
    StudySetting start{"start", {}, 1, 0, "start"};
    for (const StudyVariable& v : study.variables) start.values.push_back(v.has_start ? std::optional<double>(v.start) : std::nullopt);
    std::set<std::vector<std::pair<std::string, std::string>>> checked;
    for (std::size_t i = 0; i < study.variables.size(); ++i) {
        const StudyVariable& v = study.variables[i];
        for (const bool at_max : {false, true}) {
            StudySetting s = start;
            s.values[i] = at_max ? v.max : v.min;
            const std::string field = "variables." + v.name + (at_max ? ".max" : ".min");
            SweepVariant check{"check-" + std::to_string(variants.size()), {}, v.origin, field, {}};
            // Each variable's settings blamed on its own line: another variable's start, not this bound.
            for (std::size_t j = 0; j < study.variables.size(); ++j) {
                StudySetting alone{"", std::vector<std::optional<double>>(study.variables.size()), 1, 0, ""};
                alone.values[j] = s.values[j];
                const StudyVariable& w = study.variables[j];
                const SweepSettingOrigin o =
                    j == i ? SweepSettingOrigin{w.origin, field, "variable '" + w.name + (at_max ? "' at its max" : "' at its min")}
                           : SweepSettingOrigin{w.origin, "variables." + w.name + ".start", "variable '" + w.name + "' at its start"};
                for (auto& setting : setting_overrides(study, alone)) {
                    check.set.push_back(std::move(setting));
                    check.set_origins.push_back(o);
                }
            }
            // A setting checked already (two variables that start at a bound, or a bound that
            // reads as the start: a whole number's 127.6 is 128): once, or the plan refuses two
            // variants that set the same.
            if (checked.insert(check.set).second) variants.push_back(std::move(check));
        }
    }
    SweepPlan plan = plan_sweep_variants(variants, 1, 0, study.overrides, "");
    check_sweep_variants(study.scene_path, plan, SweepOverrides{study.overrides, study.set_origin, {}}, out);
}

// What decides which settings a search runs: everything but its budget and its confirmation (a
// larger budget goes on from the journal; more confirmation runs add to the end), comments and
// layout. A journal written under another identity is another study's. The scene is not named
// by its path: the journal's fingerprint is its hash (the runs' scene_hash, scene/resolved_writer.h:
// its settings and its meshes' bytes, however written and wherever they lie).
std::string study_identity(const Study& study, int batch) {
    std::ostringstream s;
    s.precision(17);
    for (const std::string& o : study.overrides) s << "set " << o << "\n";
    for (const StudyVariable& v : study.variables) {
        s << "variable " << v.name << ": " << v.min << " to " << v.max << " " << v.unit << ", start " << v.start
          << (v.log_scale ? ", log" : "") << (v.integer ? ", whole" : "");
        for (const auto& [path, pattern] : v.set) s << ", " << path << "=" << pattern;
        s << "\n";
    }
    s << "objective " << (study.maximise ? "maximise " : "minimise ") << study.objective
      << (study.objective_component.empty() ? "" : " of " + study.objective_component) << "\n";
    for (const StudyConstraint& c : study.constraints)
        s << "constraint " << c.figure << (c.component.empty() ? "" : " of " + c.component) << (c.is_max ? " <= " : " >= ") << c.limit
          << "\n";
    s << "design: initial " << study.initial << ", seeds " << study.seeds << ", max_seeds " << study.max_seeds << ", tolerance "
      << study.tolerance << ", batch " << batch << ", seed " << study.seed << "\n";
    return s.str();
}

// The figures of each setting, and the search's points (complete settings only).
struct MeasuredSettings {
    SettingFigures figures;
    std::vector<SearchPoint> points;
    std::vector<std::size_t> point_setting;  // setting of each point
};

// What a journal's identity and this study's differ in, for the message: the first line of the
// study's identity that differs ("variable speed ..."), or the scene file.
std::string what_differs(const JournalIdentity& journal, const JournalIdentity& now) {
    std::istringstream a(journal.study), b(now.study);
    for (std::string was, is;;) {
        const bool more_was = static_cast<bool>(std::getline(a, was)), more_is = static_cast<bool>(std::getline(b, is));
        if (!more_was && !more_is) break;
        if (was != is)
            return "its settings came from '" + (more_was ? was : std::string("(nothing)")) + "', this study has '" +
                   (more_is ? is : std::string("(nothing)")) + "'";
    }
    return journal.scene_fingerprint != now.scene_fingerprint ? "its scene has changed since (a setting, or a mesh file's bytes)"
                                                              : "it is not this study's";
}

// The standard deviation of a figure's runs from its Student's t interval over them: ci95 sqrt(n) /
// t(0.975, n - 1); 0 for one run (its interval is the run's own forecast's, not a spread of runs).
double runs_sd(const SweepFigure& f, double runs) {
    if (runs < 2.0 || !f.ci95 || !std::isfinite(*f.ci95)) return 0.0;
    return *f.ci95 * std::sqrt(runs) / student_t_two_sided_quantile(0.05, runs - 1.0);
}

MeasuredSettings measure_settings(const Study& study, const std::vector<StudySetting>& settings, const SweepPlan& plan) {
    MeasuredSettings m;
    m.figures = read_setting_figures(study, plan);
    const ObjectiveScale scale = ObjectiveScale::of(study);
    for (std::size_t k = 0; k < settings.size(); ++k) {
        if (!complete(settings[k])) continue;
        SearchPoint p;
        p.u = unit_point(study, settings[k]);
        const SweepFigure o = m.figures.at(k, study.objective_component, study.objective);
        p.y = o.mean && (!scale.log || *o.mean > 0.0) ? scale.to_model(*o.mean) : NAN;
        p.runs = static_cast<double>(std::max<std::size_t>(1, m.figures.runs(k)));
        // The runs' scatter, on the model's scale (a log: relative to the mean).
        if (std::isfinite(p.y)) {
            const double sd = runs_sd(o, p.runs);
            const double model_sd = scale.log ? sd / *o.mean : sd;
            p.scatter = (p.runs - 1.0) * model_sd * model_sd;
        }
        for (const StudyConstraint& c : study.constraints) {
            const SweepFigure g = m.figures.at(k, c.component, c.figure);
            const double norm = c.limit != 0.0 ? std::abs(c.limit) : 1.0;
            p.g.push_back(!g.mean ? NAN : (c.is_max ? *g.mean - c.limit : c.limit - *g.mean) / norm);
            const double sd = runs_sd(g, p.runs) / norm;
            p.g_scatter.push_back((p.runs - 1.0) * sd * sd);
        }
        m.points.push_back(std::move(p));
        m.point_setting.push_back(k);
    }
    return m;
}

// The next round: a replicate of the incumbent while the model's 95 % interval there is wider than
// the tolerance (its noise shrinks with its runs),
// then the model's proposals (a proposal that rounds to a setting already run adds a seed to it
// instead). Nothing added: nothing left worth a run.
struct SearchRound {
    std::vector<StudySetting> added;
    std::vector<std::string> replicated;  // settings given one more seed
    std::string incumbent;                // "e003: 1231 (1136 to 1335)", the model's best so far
};

SearchRound next_round(const Study& study, std::vector<StudySetting>& settings, const MeasuredSettings& m, int batch, int runs_left,
                       int round) {
    std::vector<StudySetting> added;
    std::vector<std::string> replicated_names;
    if (m.points.empty()) return {};
    const SearchModel model(m.points, study.constraints.size());
    const std::size_t inc = m.point_setting[model.incumbent(m.points)];
    int slots = std::min(batch, runs_left);
    std::vector<bool> replicated(settings.size(), false);
    const auto replicate = [&](std::size_t k) {
        if (replicated[k] || settings[k].seeds >= study.max_seeds || slots < 1) return false;
        ++settings[k].seeds;
        settings[k].why += settings[k].why.find("+seeds") == std::string::npos ? "+seeds" : "";
        replicated[k] = true;
        replicated_names.push_back(settings[k].name);
        --slots;
        return true;
    };
    const ObjectiveScale scale = ObjectiveScale::of(study);
    const GpPrediction at_incumbent = model.objective(unit_point(study, settings[inc]));
    const double sd = std::sqrt(at_incumbent.variance), centre = scale.to_figure(at_incumbent.mean);
    const double half = 0.5 * std::abs(scale.to_figure(at_incumbent.mean + 1.96 * sd) - scale.to_figure(at_incumbent.mean - 1.96 * sd));
    if (half > study.tolerance * std::abs(centre)) replicate(inc);
    const double a = scale.to_figure(at_incumbent.mean - 1.96 * sd), b = scale.to_figure(at_incumbent.mean + 1.96 * sd);
    std::string incumbent =
        settings[inc].name + ": " + fmt(centre, 6) + " (" + fmt(std::min(a, b), 6) + " to " + fmt(std::max(a, b), 6) + ")";
    const std::vector<Eigen::VectorXd> proposals =
        model.propose(m.points, slots, study.seed * 1000003ULL + static_cast<std::uint64_t>(round));
    for (const Eigen::VectorXd& u : proposals) {
        if (slots < study.seeds) break;
        StudySetting s{setting_name(settings.size() + added.size()), {}, study.seeds, round, "search"};
        for (std::size_t i = 0; i < study.variables.size(); ++i)
            s.values.push_back(value_of_unit(study.variables[i], u(static_cast<Eigen::Index>(i))));
        const auto same = std::find_if(settings.begin(), settings.end(), [&](const StudySetting& t) { return t.values == s.values; });
        if (same != settings.end()) {
            replicate(static_cast<std::size_t>(same - settings.begin()));
            continue;
        }
        if (std::any_of(added.begin(), added.end(), [&](const StudySetting& t) { return t.values == s.values; })) continue;
        slots -= s.seeds;
        added.push_back(std::move(s));
    }
    settings.insert(settings.end(), added.begin(), added.end());
    return {added, replicated_names, incumbent};
}

int runs_in(const std::vector<StudySetting>& settings) {
    int n = 0;
    for (const StudySetting& s : settings) n += s.seeds;
    return n;
}

}  // namespace

int optimise_job(const OptimiseOptions& options, std::ostream& out, std::ostream& err) {
    return report_errors(err, [&] { return run_optimise(options, out, err); });
}

int run_optimise(const OptimiseOptions& options, std::ostream& out, std::ostream& err) {
    if (options.output_dir.empty()) throw InputError({"-o"}, "", "expected the optimisation's output directory (-o DIR)");
    Study study = read_study_file(options.study_path);
    const SceneDescription scene = read_sweep_scene(study.scene_path, {study.overrides, study.set_origin, {}});
    fill_starts(study, scene);
    const std::string dir = options.output_dir, opt_dir = dir + "/optimise";
    const std::string executable = options.executable.empty() ? this_executable() : options.executable;
    const StopRequest stop(options.stop_requested,
                           "peensim optimise: second interrupt, stopping at once (the runs keep their last checkpoints)\n");

    std::optional<MpiSweep> mpi;
    if (launched_by_mpi()) mpi.emplace();
    SweepRunner runner{executable, study.scene_path, opt_dir + "/logs", 1, nullptr, "optimise", "optimisation"};
    if (mpi && mpi->rank() != 0) {
        // The other ranks: run what rank 0 sends, round after round, until it sends nothing.
        for (std::string text = mpi->broadcast(""); !text.empty(); text = mpi->broadcast(""))
            mpi->work(executable, study.scene_path, plan_from_text(text), runner.logs_dir, stop);
        return kExitOk;
    }
    const auto run_plan = [&](const SweepPlan& plan, const std::string& headline) {
        // Its finished and interrupted runs of another scene (a mesh rewritten in place) are not
        // taken for this study's, as a sweep's are not.
        check_finished_runs(study.scene_path, plan, {"optimisation", "setting"});
        if (mpi) {
            mpi->broadcast(plan_text(plan));
            runner.mpi = &*mpi;
        }
        return run_sweep_plan(plan, runner, stop, headline, out, err);
    };
    // The other ranks wait for rank 0's next round: told "no more" once, also when rank 0 leaves
    // by an error (else they would wait for ever).
    struct RanksRelease {
        std::optional<MpiSweep>& mpi;
        bool done = false;
        void operator()() {
            if (mpi && !done) mpi->broadcast("");
            done = true;
        }
        ~RanksRelease() { (*this)(); }
    } finish_ranks{mpi};
    {
        // A component the objective or a constraint names must be one the runs log.
        std::vector<std::string> logged = scene.output.logged_components;
        if (logged.empty())
            for (const ComponentDesc& c : scene.components)
                if (logged_by_default(c.role)) logged.push_back(c.name);
        const auto check_logged = [&](const std::string& name, const SourceLocation& where, const std::string& field) {
            if (name.empty() || std::find(logged.begin(), logged.end(), name) != logged.end()) return;
            std::string names;
            for (const std::string& l : logged) names += (names.empty() ? "" : ", ") + l;
            throw InputError(where, field,
                             "no run logs a component named '" + name + "'; expected one of the scene's logged components (" + names + ")");
        };
        check_logged(study.objective_component, study.objective_origin, "objective.component");
        for (std::size_t c = 0; c < study.constraints.size(); ++c)
            check_logged(study.constraints[c].component, study.constraints[c].origin, "constraints[" + std::to_string(c) + "].component");
        check_study(study, out);
    }

    const int d = static_cast<int>(study.variables.size());
    const int slots = mpi ? std::max(1, options.jobs) * mpi->size()
                          : (options.jobs > 0 ? options.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
    runner.jobs = mpi ? std::max(1, options.jobs) : slots;
    const int budget = options.runs.value_or(study.runs > 0 ? study.runs : 10 * d + 10);
    const int batch = study.batch > 0 ? study.batch : slots;
    const int start_seeds = std::min(std::max(2, study.seeds), study.max_seeds);
    if (budget < start_seeds + study.seeds)
        throw InputError(options.runs ? SourceLocation{"--runs"} : study.runs_origin, options.runs ? "" : "runs",
                         "expected a budget of at least " + std::to_string(start_seeds + study.seeds) + " runs (the start's " +
                             std::to_string(start_seeds) + " and one setting's " + std::to_string(study.seeds) + "), got " +
                             std::to_string(budget));
    const int wanted = study.initial > 0 ? study.initial : 2 * d + 2;
    const int initial = std::clamp(wanted, 1, (budget - start_seeds) / study.seeds);
    if (initial < wanted)
        out << "optimise: note: a budget of " << budget << " runs holds " << initial << " of the first design's " << wanted
            << " settings (the start takes " << start_seeds << ")\n";
    if (start_seeds + initial * study.seeds >= budget)
        out << "optimise: note: the budget of " << budget << " runs is spent by the start and the first design: no setting will be chosen "
            << "by the model (give runs: more than " << start_seeds + initial * study.seeds << ")\n";
    const JournalIdentity identity{study_identity(study, batch), scene_hash_hex(scene_hash(scene))};

    // The settings so far: the journal's (a resumed search), else the start and the first design.
    fs::create_directories(opt_dir);
    std::vector<StudySetting> settings;
    const std::string journal = opt_dir + "/journal.json";
    if (fs::exists(journal)) {
        JournalIdentity found;
        settings = read_journal(whole_file(journal), found);
        // Another scene only: its runs say what differs, as a sweep's would.
        if (found.study == identity.study && !(found == identity))
            check_finished_runs(study.scene_path, settings_plan(study, settings, scene.process.seed, dir), {"optimisation", "setting"});
        if (!(found == identity))
            throw InputError({"-o"}, "",
                             "'" + dir + "' holds the evaluations of another study: " + what_differs(found, identity) +
                                 "; expected the same study, or another -o");
    } else {
        // The start runs twice (unless max_seeds is 1): its two runs' scatter tells the model the
        // spread between seeds from the first round on.
        StudySetting start{"start", {}, start_seeds, 0, "start"};
        for (const StudyVariable& v : study.variables) start.values.push_back(v.has_start ? std::optional<double>(v.start) : std::nullopt);
        settings.push_back(start);
        for (const Eigen::VectorXd& u : latin_hypercube(initial, d, study.seed)) {
            StudySetting s{setting_name(settings.size()), {}, study.seeds, 0, "design"};
            for (int i = 0; i < d; ++i) s.values.push_back(value_of_unit(study.variables[static_cast<std::size_t>(i)], u(i)));
            // Whole numbers over a narrow range round two strata onto one value: one setting, more seeds.
            const auto same = std::find_if(settings.begin(), settings.end(), [&](const StudySetting& t) { return t.values == s.values; });
            if (same == settings.end())
                settings.push_back(std::move(s));
            else if (same->seeds + study.seeds <= study.max_seeds)
                same->seeds += study.seeds;
        }
    }

    // The rounds: run what the journal holds, then propose the next round from everything measured.
    SweepPlan plan;
    MeasuredSettings measured;
    int round = 0;
    for (const StudySetting& s : settings) round = std::max(round, s.round);
    std::string stopped_because;
    std::vector<std::size_t> failed;
    for (;;) {
        write_file_atomically(journal, journal_text(identity, settings));
        plan = settings_plan(study, settings, scene.process.seed, dir);
        const SweepOutcome o =
            run_plan(plan, "optimise: round " + std::to_string(round) + ", " + std::to_string(settings.size()) + " settings");
        if (o.stopped) {
            finish_ranks();
            err << "optimise: interrupted; " << o.done << "/" << o.total
                << " runs finished, the others checkpointed: run the same command to go on\n";
            return kExitInterrupted;
        }
        failed = o.failed;
        measured = measure_settings(study, settings, plan);
        if (std::none_of(measured.points.begin(), measured.points.end(), [](const SearchPoint& p) { return std::isfinite(p.y); })) {
            // Nothing to model: say why, from the runs, rather than search blind.
            if (!failed.empty() && failed.size() == plan.runs.size()) {
                err << "optimise: every run failed (" << failed.size() << " of " << plan.runs.size()
                    << "): nothing to model; why is in their logs, e.g. " << sweep_run_log(plan, runner.logs_dir, failed.front()) << "\n";
                return kExitRuntimeError;
            }
            std::string why;
            for (std::size_t k = 0; k < settings.size() && why.empty(); ++k)
                why = measured.figures.at(k, study.objective_component, study.objective).missing;
            err << "optimise: no setting gave a value of " << study.objective << " ("
                << (why.empty() ? std::string("the runs' figures.json hold none") : why)
                << "); expected a figure these runs give (see a run's analysis/report.md, e.g. " << dir
                << "/start/s0/); the runs are kept\n";
            return kExitRuntimeError;
        }
        const int used = runs_in(settings);
        if (used >= budget) {
            stopped_because = "the budget of " + std::to_string(budget) + " runs is spent";
            break;
        }
        ++round;
        const SearchRound next = next_round(study, settings, measured, batch, budget - used, round);
        if (next.added.empty() && next.replicated.empty()) {
            stopped_because = "no setting is left where the model expects an improvement worth a run";
            break;
        }
        out << "optimise: best so far " << next.incumbent << "; round " << round << ":";
        for (const std::string& name : next.replicated) out << " one more seed of " << name << ";";
        for (const StudySetting& s : next.added) {
            out << " " << s.name;
            for (std::size_t i = 0; i < study.variables.size(); ++i)
                out << " " << study.variables[i].name << "=" << study_value_text(study.variables[i], *s.values[i]);
            out << ";";
        }
        out << std::endl;  // a line as it comes, also into a log file
    }

    // The winner, and independent runs of it and of the start.
    OptimiseResult result{study,
                          scene.name.empty() ? study.scene_path : scene.name,
                          settings,
                          measured.figures,
                          {},
                          {},
                          {},
                          0,
                          scene.process.seed,
                          0,
                          "",
                          0,
                          {},
                          {}};
    result.model.emplace(measured.points, study.constraints.size());
    result.points = measured.points;
    result.point_setting = measured.point_setting;
    result.best = measured.points.empty() ? 0 : measured.point_setting[result.model->incumbent(measured.points)];
    result.budget = budget;
    result.stopped_because = stopped_because;
    if (study.confirm > 0) {
        // Named by the settings: a search resumed with a larger budget may find another winner.
        std::vector<SweepVariant> variants{
            {"confirm-start", setting_overrides(study, settings[0]), SourceLocation{study.path, 0, 0}, "start", {}}};
        if (result.best != 0)
            variants.push_back({"confirm-" + settings[result.best].name,
                                setting_overrides(study, settings[result.best]),
                                SourceLocation{study.path, 0, 0},
                                "best",
                                {}});
        result.confirm_plan = plan_sweep_variants(variants, study.confirm, scene.process.seed + kConfirmSeedOffset, study.overrides, dir);
        const SweepOutcome o = run_plan(*result.confirm_plan, "optimise: confirming the winner and the start");
        if (o.stopped) {
            finish_ranks();
            err << "optimise: interrupted while confirming; run the same command to go on\n";
            return kExitInterrupted;
        }
        failed.insert(failed.end(), o.failed.begin(), o.failed.end());
        result.confirmed = read_setting_figures(study, *result.confirm_plan);
    }
    finish_ranks();
    result.failed_runs = failed.size();  // the search's and the confirmation's
    const OptimiseReportFiles files = write_optimise_report(result, opt_dir);
    out << "optimise: " << stopped_because << "; the winner is " << settings[result.best].name << "\n" << files.summary;
    out << "report: " << opt_dir << "/{report.md, report.html, evaluations.csv, winner.json" << (files.plots ? ", *.png" : "") << "}\n"
        << sweep_geometry_cache_line(opt_dir + "/logs");
    if (failed.empty()) return kExitOk;
    const bool one = failed.size() == 1;
    err << "optimise: " << failed.size() << (one ? " run failed for good (why: its log in " : " runs failed for good (why: their logs in ")
        << opt_dir << "/logs); the model leaves " << (one ? "it" : "them") << " out\n";
    return kExitRuntimeError;
}

}  // namespace peensim
