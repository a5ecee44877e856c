// The settings an optimisation evaluates (a value per study variable), how they map to the unit
// cube the search works in and to the scene's overrides, and the journal that makes a search
// resumable: every setting in the order it was proposed, with its replicates, written before its
// runs start (DIR/optimise/journal.json).
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "app/optimise/study_file.h"
#include "app/sweep/sweep_compare.h"
#include "app/sweep/sweep_plan.h"
#include "scene/scene_description.h"

namespace peensim {

struct StudySetting {
    std::string name;                           // its runs' directory: "start", "e001", ...
    std::vector<std::optional<double>> values;  // per variable, in its unit; none: the scene's own (the start only)
    int seeds = 1;                              // its replicates so far
    int round = 0;                              // when it was proposed (0: the first design)
    std::string why;                            // "start", "design", "search", or "replicate" rounds added seeds
};

// Whether every variable has a value (the start may leave some to the scene).
bool complete(const StudySetting& s);

// A value to [0, 1] and back (log scale, whole numbers), and the value as written and read back
// (6 significant digits): what the runs are given is what the model is fitted on.
double unit_of_value(const StudyVariable& v, double value);
double value_of_unit(const StudyVariable& v, double u);
Eigen::VectorXd unit_point(const Study& study, const StudySetting& s);  // complete settings only

// The scene overrides a setting gives its runs: each variable's fields with its value.
std::vector<std::pair<std::string, std::string>> setting_overrides(const Study& study, const StudySetting& s);

// Each variable without a `start` starts at the scene's own value (a `path` variable's: the
// resolved scene's, in the variable's unit); that value must lie within the bounds, as a written
// start must. A variable that writes several fields through templates has no one value to read:
// it needs `start`. Throws InputError at the variable's line.
void fill_starts(Study& study, const SceneDescription& scene);

// The plan of the settings' runs in `output_dir` (a directory per setting, s<k> per replicate,
// process.seed from base_seed), checked as a sweep's.
SweepPlan settings_plan(const Study& study, const std::vector<StudySetting>& settings, std::uint64_t base_seed,
                        const std::string& output_dir);

// The figures a study names, per setting of a plan: those of the first logged component (the part)
// and of any other component the objective or a constraint names (an Almen strip).
struct SettingFigures {
    std::map<std::string, SweepFigures> by_component;  // "" = the first logged
    SweepFigure at(std::size_t setting, const std::string& component, const std::string& figure) const;
    std::size_t runs(std::size_t setting) const;  // finished runs read
    const SweepFigures& part() const { return by_component.at(""); }
};
// Throws InputError (at the study's line) for a component no run logs.
SettingFigures read_setting_figures(const Study& study, const SweepPlan& plan);

// What the journal holds to know its study again: what decides which settings a search runs (a
// line per key: set, each variable, the objective, each constraint, the design keys; not `runs`
// or `confirm`, not comments or layout), and the scene's hash with the study's set (its runs'
// scene_hash: settings and meshes' bytes, not the file's text or path).
struct JournalIdentity {
    std::string study;
    std::string scene_fingerprint;
    bool operator==(const JournalIdentity&) const = default;
};

// The journal: its identity and the settings. Throws std::runtime_error for one it cannot read.
std::string journal_text(const JournalIdentity& identity, const std::vector<StudySetting>& settings);
std::vector<StudySetting> read_journal(const std::string& text, JournalIdentity& identity);

// A SweepPlan's runs as text and back: what rank 0 of an MPI job tells the other ranks to run.
std::string plan_text(const SweepPlan& plan);
SweepPlan plan_from_text(const std::string& text);

// The objective as the search models it, minimised: a time (a figure in s, always positive) on a log
// scale, since times vary by factors and their noise grows with them; a maximised figure negated.
struct ObjectiveScale {
    bool log = false;
    double sign = 1.0;
    static ObjectiveScale of(const Study& study);
    double to_model(double figure) const { return sign * (log ? std::log(figure) : figure); }
    double to_figure(double model) const { return log ? std::exp(sign * model) : sign * model; }
};

}  // namespace peensim
