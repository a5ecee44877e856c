// A study file: what `peensim optimise` searches (the process variables, each with bounds and its
// unit), for what (the objective, under constraints), and with what budget:
//
//   scene: ../scenes/rotating-gear.yaml        # relative to this file
//   set: ["process.duration=5 s"]              # every run, as --set
//   variables:
//     speed: {path: components[gear].motion.speed, min: 10 rpm, max: 120 rpm, start: 30 rpm}
//     height:                                  # one value written into several fields
//       min: 36 mm
//       max: 48 mm
//       start: 42 mm
//       set: {components[gear].translation: "[0, 0, {}]", components[axle].translation: "[0, 0, {}]"}
//   objective: time_to_target_everywhere_s     # or {figure: uniformity, goal: maximise}
//   constraints: [{figure: almen_predicted_intensity_m, component: almen, max: 0.25 mm}]
//   runs: 24                                   # the search's budget (start and first design included)
//
// Figures are the columns of a sweep's comparison.csv (sweep_compare.h), per region too.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/input_error.h"

namespace peensim {

struct StudyVariable {
    std::string name;
    // Where its value goes: (scene path, template) pairs, "{}" in the template replaced by the value
    // with its unit ("[0, 0, {}]"); a `path` variable is one pair with the template "{}".
    std::vector<std::pair<std::string, std::string>> set;
    double min = 0.0, max = 0.0;  // in `unit`
    std::string unit;             // as written after the bounds' numbers ("rpm"; "" for a plain number)
    bool has_start = false;
    double start = 0.0;
    bool log_scale = false;  // searched on log(value): for ranges over decades
    bool integer = false;    // a count: whole numbers only
    SourceLocation origin;
};

struct StudyConstraint {
    std::string figure;
    std::string component;  // the logged component whose figure it is ("" = the first logged: the part)
    bool is_max = true;     // figure <= limit (false: figure >= limit)
    double limit = 0.0;
    SourceLocation origin;
};

struct Study {
    std::string path;        // the study file
    std::string scene_path;  // resolved against the study file's directory
    std::vector<std::string> overrides;
    SourceLocation set_origin;
    std::vector<StudyVariable> variables;
    std::string objective = "time_to_target_everywhere_s";
    std::string objective_component;  // "" = the first logged component (the part); an Almen strip's name for its intensity
    bool maximise = false;
    SourceLocation objective_origin;
    std::vector<StudyConstraint> constraints;
    int runs = 0;                // the search's budget of runs (0: not given; the default is the job's)
    SourceLocation runs_origin;  // the `runs` key (the file's start when not given)
    int initial = 0;             // settings of the first design (0: 2 d + 2)
    int seeds = 1;               // replicates of a new setting
    int max_seeds = 4;           // replicates of one setting at most
    double tolerance = 0.05;     // the winner's interval half-width, as a share of its value, below which it needs no more seeds
    int batch = 0;               // settings per round (0: the runs that go at once)
    int confirm = 5;             // independent runs of the winner and the start at the end
    std::uint64_t seed = 1;      // the search's own random stream
};

// The figures a study may name: comparison.csv's, and region_<name>_{impact_rate_per_s, coverage,
// time_to_target_s}.
bool is_study_figure(const std::string& name);

// Throws InputError (file, line, field, what was expected) for anything a search cannot use.
Study read_study_file(const std::string& path);

// A value of a variable as the scene reads it: 6 significant digits, then the unit ("37.5 rpm").
std::string study_value_text(const StudyVariable& v, double value);

}  // namespace peensim
