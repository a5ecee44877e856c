// `peensim optimise` (app/optimise/optimise_job.h) end to end. A known process first: the runs are
// a stand-in program (a script given as the runs' executable) whose time to the target is
// 1000 s x (1 + (rpm - 70)^2 / 2000 + (height - 40 mm)^2 / 50) with 3 % noise per run, on the real
// rotating-gear scene's fields (every setting is checked by the real scene reader). The search
// finds the optimum, confirms it with new seeds, resumes without rerunning, extends its budget,
// refuses another study's directory, finds a constraint's boundary, and its predicted interval
// holds the truth at the winner in most of 12 searches. Then real runs of the rod, locally and
// over MPI ranks: the same settings in the same order, the same runs.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/exit_codes.h"
#include "app/optimise/optimise_job.h"
#include "support/child_process.h"
#include "support/files.h"
#include "support/mpirun_environment.h"
#include "support/shipped_scenes.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace peensim::testing {
namespace optimise_job_cases {
namespace {

// The stand-in for `peensim run`: reads the --set values, writes a finished run's summary and
// figures. Its noise is a function of the seed and the setting (Python's string seeding is SHA-512).
constexpr const char* kFakeRun = R"(#!/usr/bin/python3
import json, os, random, sys
args = sys.argv[1:]
out = args[args.index("-o") + 1]
sets = dict(args[i + 1].split("=", 1) for i, a in enumerate(args) if a == "--set")
rpm = float(sets.get("components[gear].motion.speed", "30 rpm").split()[0])
height = float(sets.get("components[gear].translation", "[0, 0, 42 mm]").strip("[]").split(",")[2].split()[0])
seed = sets.get("process.seed", "1")
if rpm > float(os.environ.get("FAKE_FAIL_ABOVE_RPM", "1e9")):
    sys.exit(1)
noise = random.Random("%s %r %r" % (seed, rpm, height)).gauss(0.0, 1.0)
t = 1000.0 * (1.0 + (rpm - 70.0) ** 2 / 2000.0 + (height - 40.0) ** 2 / 50.0) * (1.0 + 0.03 * noise)
os.makedirs(out + "/analysis", exist_ok=True)
json.dump({"finished": True, "normal_speed": []}, open(out + "/summary.json", "w"))
json.dump({"target_coverage": 0.98, "components": [{"component": "gear", "impact_rate_per_s": 1000.0, "mean_vn_mps": 2.0,
           "coverage": 0.1, "almen_dose_J_per_m2": 10.0 + rpm / 5.0, "almen_predicted_intensity_m": 1e-4 * (1.0 + rpm / 100.0),
           "time_to_target_everywhere": {"status": "forecast", "time_s": t, "low_s": 0.8 * t, "high_s": 1.25 * t}}]},
          open(out + "/analysis/figures.json", "w"))
)";

// The process' time at a setting (the stand-in's without noise).
double truth(double rpm, double height_mm) {
    return 1000.0 * (1.0 + (rpm - 70.0) * (rpm - 70.0) / 2000.0 + (height_mm - 40.0) * (height_mm - 40.0) / 50.0);
}

std::string fake_run(const fs::path& dir) {
    const fs::path path = dir / "fake-peensim";
    std::ofstream(path) << kFakeRun;
    ::chmod(path.c_str(), 0755);
    return path.string();
}

std::string study_text(const std::string& extra = "") {
    return "scene: " + std::string(PEENSIM_SOURCE_DIR) + "/scenes/rotating-gear.yaml\n" +
           "variables:\n"
           "  speed: {path: \"components[gear].motion.speed\", min: 15 rpm, max: 120 rpm, start: 30 rpm}\n"
           "  height:\n"
           "    min: 32 mm\n"
           "    max: 50 mm\n"
           "    start: 45 mm\n"
           "    set:\n"
           "      components[gear].translation: \"[0, 0, {}]\"\n"
           "      components[axle].translation: \"[0, 0, {}]\"\n"
           "      components[gear].motion.axis_point: \"[0, 0, {}]\"\n"
           "runs: 24\n" +
           extra;
}

OptimiseOptions options(const fs::path& study, const fs::path& out, const std::string& executable) {
    OptimiseOptions o;
    o.study_path = study.string();
    o.output_dir = out.string();
    o.jobs = 2;
    o.executable = executable;
    return o;
}

// A number after `key` on the line that starts with `line_start` in `text` (NaN if none).
double number_after(const std::string& text, const std::string& line_start, const std::string& key) {
    const auto b = text.find(line_start);
    if (b == std::string::npos) return NAN;
    const auto k = text.find(key, b);
    return k == std::string::npos ? NAN : std::atof(text.c_str() + k + key.size());
}

// The winner's row of evaluations.csv (its name from the report) as cells.
std::vector<std::string> winner_row(const fs::path& dir) {
    const std::string report = read_file(dir / "optimise" / "report.md");
    const auto b = report.find("## The winner: `") + 16;
    const std::string name = report.substr(b, report.find('`', b) - b);
    std::istringstream csv(read_file(dir / "optimise" / "evaluations.csv"));
    for (std::string line; std::getline(csv, line);)
        if (line.rfind(name + ",", 0) == 0) {
            std::vector<std::string> cells;
            std::istringstream row(line);
            for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
            return cells;
        }
    return {};
}

TEST(OptimiseJob, FindsConfirmsAndResumesTheOptimumOfAKnownProcess) {
    TempDir dir;
    const std::string fake = fake_run(dir.path);
    std::ofstream(dir.path / "study.yaml") << study_text();
    std::ostringstream out, err;
    ASSERT_EQ(optimise_job(options(dir.path / "study.yaml", dir.path / "o", fake), out, err), kExitOk) << err.str() << out.str();
    // The winner: near 70 rpm and 40 mm; its cells: setting, round, why, speed_rpm, height_mm, ...
    const std::vector<std::string> w = winner_row(dir.path / "o");
    ASSERT_GE(w.size(), 8u);
    const double rpm = std::stod(w[3]), height = std::stod(w[4]);
    EXPECT_NEAR(rpm, 70.0, 20.0) << out.str();
    EXPECT_NEAR(height, 40.0, 1.5) << out.str();
    EXPECT_LT(truth(rpm, height), 1.05 * 1000.0);
    const std::string report = read_file(dir.path / "o" / "optimise" / "report.md");
    // Confirmed by 3 new runs of each: better than the start (2300 s) beyond noise; the prediction holds.
    EXPECT_NE(report.find("**Against the start:** better by"), std::string::npos) << report;
    EXPECT_NE(report.find("differs"), std::string::npos) << report;
    EXPECT_NE(report.find("**The winner's prediction holds:**"), std::string::npos) << report;
    EXPECT_NE(report.find("**The predicted improvement holds:**"), std::string::npos) << report;
    EXPECT_NEAR(number_after(report, "| start, confirmed |", "confirmed | "), truth(30.0, 45.0), 0.1 * truth(30.0, 45.0)) << report;
    EXPECT_TRUE(fs::exists(dir.path / "o" / "confirm-start" / "s2" / "summary.json"));
    EXPECT_NE(report.find("peensim run "), std::string::npos);  // the command that reproduces it
    for (const char* png : {"objective_vs_speed_rpm.png", "objective_vs_height_mm.png", "search_progress.png"})
        EXPECT_TRUE(fs::exists(dir.path / "o" / "optimise" / png)) << png;
    EXPECT_NE(out.str().find("optimise: best so far "), std::string::npos) << out.str();
    // The budget: 24 runs in the search (each setting's seeds, column 5).
    int runs = 0;
    std::istringstream csv(read_file(dir.path / "o" / "optimise" / "evaluations.csv"));
    std::string line;
    std::getline(csv, line);
    while (std::getline(csv, line)) {
        std::istringstream row(line);
        std::string cell;
        for (int k = 0; k <= 5; ++k) std::getline(row, cell, ',');
        runs += std::stoi(cell);
    }
    EXPECT_EQ(runs, 24);

    // Again: nothing reruns, the same report byte for byte.
    std::ostringstream again, again_err;
    ASSERT_EQ(optimise_job(options(dir.path / "study.yaml", dir.path / "o", fake), again, again_err), kExitOk) << again_err.str();
    EXPECT_EQ(read_file(dir.path / "o" / "optimise" / "report.md"), report);
    EXPECT_EQ(again.str().find(" done ("), std::string::npos) << again.str();  // no run's progress line: none ran
    // A larger budget goes on from there.
    OptimiseOptions more = options(dir.path / "study.yaml", dir.path / "o", fake);
    more.runs = 28;
    std::ostringstream extended, extended_err;
    ASSERT_EQ(optimise_job(more, extended, extended_err), kExitOk) << extended_err.str();
    EXPECT_NE(extended.str().find("finished before"), std::string::npos) << extended.str();
    EXPECT_NE(read_file(dir.path / "o" / "optimise" / "report.md").find("runs of the search (budget 28)"), std::string::npos);
    // Another study in the same directory is refused.
    std::ofstream(dir.path / "study.yaml") << study_text("seeds: 2\n");
    std::ostringstream other, other_err;
    EXPECT_EQ(optimise_job(options(dir.path / "study.yaml", dir.path / "o", fake), other, other_err), kExitInputError);
    EXPECT_NE(other_err.str().find("holds the evaluations of another study"), std::string::npos) << other_err.str();
}

// A window: an intensity (a component named, as an Almen strip's would be) at least 0.15 mm (1e-4 m
// x (1 + rpm / 100): at least 50 rpm), the Almen dose at most 22 J/m2 (10 + rpm / 5: at most 60
// rpm). The optimum (70 rpm) is outside: the winner sits at the window's edge, 60 rpm.
TEST(OptimiseJob, AConstraintsBoundaryIsTheWinner) {
    TempDir dir;
    std::ofstream(dir.path / "study.yaml") << study_text(
        "constraints: [{figure: almen_dose_J_per_m2, max: 22}, {figure: almen_predicted_intensity_m, component: gear, min: 1.5e-4}]\n"
        "confirm: 0\n");
    std::ostringstream out, err;
    ASSERT_EQ(optimise_job(options(dir.path / "study.yaml", dir.path / "o", fake_run(dir.path)), out, err), kExitOk) << err.str();
    const std::vector<std::string> w = winner_row(dir.path / "o");
    ASSERT_GE(w.size(), 12u);
    const double rpm = std::stod(w[3]);
    EXPECT_LE(10.0 + rpm / 5.0, 22.0 + 1e-9);
    EXPECT_GT(rpm, 55.0);
    EXPECT_NEAR(std::stod(w[4]), 40.0, 1.5);
    const std::string report = read_file(dir.path / "o" / "optimise" / "report.md");
    EXPECT_NE(report.find("| `almen_dose_J_per_m2` <= 22 | "), std::string::npos) << report;
    EXPECT_NE(report.find("| `almen_predicted_intensity_m` >= 0.00015 | "), std::string::npos) << report;
    // A component no run logs is an input error at the constraint's line, before anything runs.
    std::ofstream(dir.path / "study.yaml") << study_text("constraints: [{figure: coverage, component: strip, min: 0.5}]\nconfirm: 0\n");
    std::ostringstream bad, bad_err;
    EXPECT_EQ(optimise_job(options(dir.path / "study.yaml", dir.path / "bad", fake_run(dir.path)), bad, bad_err), kExitInputError);
    EXPECT_NE(bad_err.str().find("study.yaml:13:15: constraints[0].component: no run logs a component named 'strip'; expected one of the "
                                 "scene's logged components (gear)"),
              std::string::npos)
        << bad_err.str();
    EXPECT_FALSE(fs::exists(dir.path / "bad" / "start"));
}

// Runs that fail (every one above 100 rpm): retried once, then counted as the worst measured; the
// search goes on around them, the report says so, and the command ends with exit 1.
TEST(OptimiseJob, FailedRunsCountAsTheWorstAndTheSearchGoesOn) {
    TempDir dir;
    std::ofstream(dir.path / "study.yaml") << study_text("confirm: 2\n");
    ::setenv("FAKE_FAIL_ABOVE_RPM", "100", 1);
    std::ostringstream out, err;
    const int code = optimise_job(options(dir.path / "study.yaml", dir.path / "o", fake_run(dir.path)), out, err);
    ::unsetenv("FAKE_FAIL_ABOVE_RPM");
    EXPECT_EQ(code, kExitRuntimeError) << err.str();
    const std::vector<std::string> w = winner_row(dir.path / "o");
    ASSERT_GE(w.size(), 5u) << out.str();
    EXPECT_NEAR(std::stod(w[3]), 70.0, 20.0);
    EXPECT_NE(read_file(dir.path / "o" / "optimise" / "report.md").find("runs failed (twice, or once refusing their input)"),
              std::string::npos);
    // Each failure said as the optimisation's, and their count at the end.
    EXPECT_NE(err.str().find("; the optimisation goes on without it"), std::string::npos) << err.str();
    EXPECT_NE(err.str().find("runs failed for good (why: their logs in " + (dir.path / "o" / "optimise" / "logs").string() +
                             "); the model leaves them out"),
              std::string::npos)
        << err.str();
}

// A variable without `start` starts at the scene's own value (the gear's 30 rpm), and the start's
// runs are in the model; whole numbers over a narrow range (1 to 3 mm) put two strata of the first
// design on one value: one setting with more seeds, not an error.
TEST(OptimiseJob, TheStartIsTheScenesOwnValueAndADesignOnFewWholeValuesMerges) {
    TempDir dir;
    const std::string scene = "scene: " + std::string(PEENSIM_SOURCE_DIR) + "/scenes/rotating-gear.yaml\n";
    std::ofstream(dir.path / "study.yaml")
        << scene << "variables:\n  speed: {path: \"components[gear].motion.speed\", min: 15 rpm, max: 120 rpm}\n"
        << "  size: {path: shot.diameter, min: 1 mm, max: 3 mm, integer: true}\nruns: 12\ninitial: 6\nconfirm: 0\n";
    std::ostringstream out, err;
    ASSERT_EQ(optimise_job(options(dir.path / "study.yaml", dir.path / "o", fake_run(dir.path)), out, err), kExitOk) << err.str();
    const std::string journal = read_file(dir.path / "o" / "optimise" / "journal.json");
    EXPECT_NE(journal.find("\"values\": [\n    30.0,\n    2.0\n   ]"), std::string::npos) << journal;  // the scene's 30 rpm, 2 mm
    const std::string csv = read_file(dir.path / "o" / "optimise" / "evaluations.csv");
    EXPECT_NE(csv.find("start,0,start,30,2,2,2,"), std::string::npos) << csv;
    EXPECT_NE(read_file(dir.path / "o" / "optimise" / "report.md").find("the model over all "), std::string::npos);
}

// Variables that start at their min (a whole number's 127.6 reads as 128): the check's settings at
// each bound (the others at the start) hold that one more than once, checked once (it was refused:
// "variant 'check-2' sets the same values as variant 'check-0'").
TEST(OptimiseJob, VariablesThatStartAtABoundAreAccepted) {
    TempDir dir;
    std::ofstream(dir.path / "study.yaml")
        << "scene: " << PEENSIM_SOURCE_DIR << "/scenes/rotating-gear.yaml\n"
        << "variables:\n  speed: {path: \"components[gear].motion.speed\", min: 15 rpm, max: 120 rpm, start: 15 rpm}\n"
        << "  size: {path: shot.diameter, min: 1 mm, max: 3 mm, start: 1 mm}\n"
        << "  count: {path: shot.count, min: 127.6, max: 140, start: 128, integer: true}\nruns: 8\ninitial: 4\nconfirm: 0\n";
    std::ostringstream out, err;
    ASSERT_EQ(optimise_job(options(dir.path / "study.yaml", dir.path / "o", fake_run(dir.path)), out, err), kExitOk) << err.str();
    EXPECT_NE(read_file(dir.path / "o" / "optimise" / "evaluations.csv").find("start,0,start,15,1,128,"), std::string::npos);
}

// An objective no run gives (the stand-in writes no uniformity): exit 1 saying so, no winner made up.
TEST(OptimiseJob, AnObjectiveNoRunGivesEndsTheSearchSayingSo) {
    TempDir dir;
    std::ofstream(dir.path / "study.yaml") << study_text("objective: {figure: uniformity, goal: maximise}\n");
    std::ostringstream out, err;
    EXPECT_EQ(optimise_job(options(dir.path / "study.yaml", dir.path / "o", fake_run(dir.path)), out, err), kExitRuntimeError);
    EXPECT_NE(err.str().find("optimise: no setting gave a value of uniformity"), std::string::npos) << err.str();
    EXPECT_FALSE(fs::exists(dir.path / "o" / "optimise" / "winner.json"));
    EXPECT_EQ(out.str().find("round 1"), std::string::npos) << out.str();
}

// Runs that all refuse their input (exit 2: here a stand-in that always does) are not run again,
// and the search ends saying so and where their logs are, not blaming the objective.
TEST(OptimiseJob, EveryRunRefusedEndsSayingWhereTheirLogsAre) {
    TempDir dir;
    std::ofstream(dir.path / "study.yaml") << study_text("runs: 8\ninitial: 4\n");
    const fs::path refusing = dir.path / "refusing";
    std::ofstream(refusing) << "#!/bin/sh\necho 'error: gear.step: mesh: reading STEP/IGES needs libpeensim_cad.so' >&2\nexit 2\n";
    ::chmod(refusing.c_str(), 0755);
    std::ostringstream out, err;
    EXPECT_EQ(optimise_job(options(dir.path / "study.yaml", dir.path / "o", refusing.string()), out, err), kExitRuntimeError);
    EXPECT_NE(err.str().find("optimise: every run failed ("), std::string::npos) << err.str();
    EXPECT_NE(err.str().find((dir.path / "o" / "optimise" / "logs").string() + "/"), std::string::npos) << err.str();
    EXPECT_EQ(err.str().find("no setting gave a value"), std::string::npos) << err.str();
    EXPECT_EQ(err.str().find("trying it once more"), std::string::npos) << err.str();
    EXPECT_FALSE(fs::exists(dir.path / "o" / "optimise" / "winner.json"));
}

// The claim of the predicted interval at the winner: over 12 searches (their own search seeds), the
// truth lies in it in at least 9 (95 % nominal; the winner is picked for looking good, and the
// model's hyperparameters come from ~20 settings).
TEST(OptimiseJob, ThePredictedIntervalAtTheWinnerHoldsTheTruth) {
    TempDir dir;
    const std::string fake = fake_run(dir.path);
    int held = 0;
    std::string lines;
    for (int seed = 1; seed <= 12; ++seed) {
        const fs::path study = dir.path / ("study" + std::to_string(seed) + ".yaml");
        std::ofstream(study) << study_text("confirm: 0\nseed: " + std::to_string(seed) + "\n");
        std::ostringstream out, err;
        ASSERT_EQ(optimise_job(options(study, dir.path / ("o" + std::to_string(seed)), fake), out, err), kExitOk) << err.str();
        const std::vector<std::string> w = winner_row(dir.path / ("o" + std::to_string(seed)));
        ASSERT_GE(w.size(), 12u);
        const double t = truth(std::stod(w[3]), std::stod(w[4])), low = std::stod(w[10]), high = std::stod(w[11]);
        held += low <= t && t <= high;
        lines += w[3] + " rpm " + w[4] + " mm: truth " + std::to_string(t) + " in [" + w[10] + ", " + w[11] + "]\n";
    }
    EXPECT_GE(held, 9) << lines;
    std::cout << "the truth at the winner lay in the predicted 95 % interval in " << held << " of 12 searches\n" << lines;
}

TEST(OptimiseJob, BadStudiesAreInputErrorsNamingTheLineAndField) {
    TempDir dir;
    const std::string scene = "scene: " + std::string(PEENSIM_SOURCE_DIR) + "/scenes/rotating-gear.yaml\n";
    const std::string speed = "variables:\n  speed: {path: \"components[gear].motion.speed\", min: 15 rpm, max: 120 rpm}\n";
    const struct {
        std::string text, expected;
    } cases[] = {
        {scene + speed + "budget: 3\n", "study.yaml:4:1: budget: unknown key in a study file; expected scene, set, variables"},
        {scene, "variables: missing the variables"},
        {speed, "scene: missing the scene file"},
        {scene + "variables:\n  speed: {path: \"components[gear].motion.speed\", min: 120 rpm, max: 15 rpm}\n",
         "study.yaml:3:69: variables.speed.max: expected max above min (120 rpm)"},
        {scene + "variables:\n  speed: {path: \"components[gear].motion.speed\", min: 15 rpm, max: 2 rad/s}\n",
         "variables.speed.max: expected the unit of min ('rpm'), got 'rad/s'"},
        {scene + "variables:\n  speed: {path: \"components[gear].motion.speed\", min: 15 rpm, max: 120 rpm, start: 200 rpm}\n",
         "variables.speed.start: expected a start within min and max"},
        {scene + "variables:\n  speed: {path: \"components[gear].motion.speed\", min: 0 rpm, max: 120 rpm, scale: log}\n",
         "variables.speed.scale: a log scale needs min above 0"},
        {scene + "variables:\n  count: {path: shot.count, min: 10.2, max: 10.9, integer: true}\n",
         "variables.count.integer: expected at least two whole numbers between min and max"},
        {scene + "variables:\n  speed: {min: 15 rpm, max: 120 rpm}\n", "variables.speed: expected path (the scene field it sets) or set"},
        {scene + "variables:\n  h: {min: 1 mm, max: 2 mm, set: {\"components[gear].translation\": \"[0, 0, 1 mm]\"}}\n",
         "variables.h.set.components[gear].translation: expected a template with {} where the value goes"},
        {scene + speed + "objective: fastest\n", "study.yaml:4:12: objective: expected one of impact_rate_per_s"},
        {scene + speed + "objective: {figure: uniformity, goal: best}\n", "objective.goal: expected minimise or maximise, got 'best'"},
        {scene + speed + "constraints: [{figure: almen_dose_J_per_m2}]\n", "constraints[0]: expected one limit: max or min"},
        {scene + speed + "constraints: [{figure: almen_dose_J_per_m2, max: 20 J/m2}]\n",
         "constraints[0].max: expected a plain number in the figure's SI unit"},
        {scene + speed + "runs: 1\n", "runs: expected a whole number from 2 to 5000, got '1'"},
        {scene + speed + "tolerance: 150 %\n", "tolerance: expected a share of the winner's value above 0 and below 1"},
        {scene + speed + "seeds: 3\nmax_seeds: 2\n", "max_seeds: expected at least `seeds` (3)"},
        // A path the scene does not have, and a bound the scene refuses: blamed on the variable's line.
        {scene + "variables:\n  speed: {path: \"components[gear].motion.sped\", min: 15 rpm, max: 120 rpm}\n",
         "study.yaml:3:3: variables.speed.path: 'components[gear].motion.sped' is no scene field"},
        {scene + "variables:\n  size: {path: shot.diameter, min: -1 mm, max: 2 mm}\n", "study.yaml:3:3: variables.size.min: "},
        // Another variable's start the scene refuses: blamed on that variable, not on the bound checked.
        {scene + speed + "  h: {min: 30 mm, max: 50 mm, start: 40 mm, set: {\"components[gear].translation\": \"[0, 0, {}, 1]\"}}\n",
         "study.yaml:4:3: variables.h.start: "},
        {scene + "variables:\n  speed: {path: components[gear].motion.speed, min: 15 rpm, max: 120 rpm}\n", "study.yaml:3:"},
        {scene + speed + "  speed: {path: shot.count, min: 10, max: 100}\n",
         "study.yaml:4:3: variables.speed: a second variable named 'speed'"},
        {scene + speed + "  rpm: {path: \"components[gear].motion.speed\", min: 10 rpm, max: 20 rpm}\n",
         "study.yaml:4:3: variables.rpm: sets components[gear].motion.speed as variables.speed does (line 3)"},
        {scene + speed + "confirm: 1\n", "study.yaml:4:10: confirm: expected 0 (none) or 2 and more"},
        {"scene: nothere.yaml\n" + speed, "study.yaml:1:8: scene: no scene file at"},
        {scene + speed + "runs: 2\n",
         "study.yaml:4:7: runs: expected a budget of at least 3 runs (the start's 2 and one setting's 1), got 2"},
        // The start from the scene (30 rpm) outside the bounds; a template variable without a start.
        {scene + "variables:\n  speed: {path: \"components[gear].motion.speed\", min: 40 rpm, max: 120 rpm}\n",
         "study.yaml:3:3: variables.speed.start: the scene's own value, 30 rpm, is outside min and max"},
        {scene + "variables:\n  h: {min: 30 mm, max: 50 mm, set: {\"components[gear].translation\": \"[0, 0, {}]\"}}\n",
         "variables.h.start: a variable that sets several fields has no one scene value to start from; expected start:"},
    };
    for (const auto& c : cases) {
        std::ofstream(dir.path / "study.yaml") << c.text;
        std::ostringstream out, err;
        EXPECT_EQ(optimise_job(options(dir.path / "study.yaml", dir.path / "o", "/bin/false"), out, err), kExitInputError) << c.text;
        EXPECT_NE(err.str().find(c.expected), std::string::npos) << c.text << "\n" << err.str();
        EXPECT_FALSE(fs::exists(dir.path / "o" / "optimise" / "journal.json")) << c.text;  // nothing started
    }
}

// Real runs of the rod (20 ms each): the count of shot that maximises the impact rate, locally and
// under `mpirun -n 2`: the same settings in the same order (the journal byte for byte) and the same
// runs (a run's impact log byte for byte).
TEST(OptimiseMpi, RanksRunTheSameSearchAsOneProcess) {
    const std::string mpirun = "/usr/bin/mpirun";
    ASSERT_TRUE(fs::exists(mpirun)) << "mpirun not found: .ci/install-deps installs openmpi-bin";
    TempDir dir;
    std::ofstream(dir.path / "study.yaml")
        << "scene: " << kRod << "\nset: [\"process.duration=20 ms\"]\n"
        << "variables:\n  count: {path: shot.count, min: 32, max: 160, integer: true, start: 64}\n"
        << "objective: {figure: impact_rate_per_s, goal: maximise}\nruns: 6\ninitial: 3\nbatch: 2\nconfirm: 2\n";
    std::ostringstream out, err;
    OptimiseOptions local = options(dir.path / "study.yaml", dir.path / "local", PEENSIM_BINARY);
    local.jobs = 1;
    ASSERT_EQ(optimise_job(local, out, err), kExitOk) << err.str() << out.str();
    mpirun_environment();
#if defined(__SANITIZE_ADDRESS__)
    // The runs under the ranks analyse and draw the report's pictures (OSMesa's LLVM JIT), which
    // deadlocks under the whole-stack unwinding Open MPI's leak suppressions need: here the ranks and
    // their runs check memory errors, not leaks (the optimiser's own leaks: OptimiseJob.*, in process).
    ::setenv("ASAN_OPTIONS", "detect_leaks=0:abort_on_error=1:allocator_may_return_null=1", 1);
#endif
    ChildProcess mpi({mpirun, "-n", "2", "--oversubscribe", PEENSIM_BINARY, "optimise", (dir.path / "study.yaml").string(), "-o",
                      (dir.path / "mpi").string()},
                     (dir.path / "mpi.out").string(), (dir.path / "mpi.err").string());
    ASSERT_EQ(mpi.wait_exit(600.0), std::optional<int>(kExitOk)) << read_file(dir.path / "mpi.err") << read_file(dir.path / "mpi.out");
    const std::string said = read_file(dir.path / "mpi.out");
    EXPECT_NE(said.find("runs over 2 MPI ranks"), std::string::npos) << said;
    EXPECT_EQ(said.find("report: "), said.rfind("report: ")) << said;  // rank 0's, once
    EXPECT_EQ(read_file(dir.path / "mpi" / "optimise" / "journal.json"), read_file(dir.path / "local" / "optimise" / "journal.json"));
    EXPECT_EQ(read_file(dir.path / "mpi" / "e001" / "s0" / "impacts.csv"), read_file(dir.path / "local" / "e001" / "s0" / "impacts.csv"));
    EXPECT_EQ(winner_row(dir.path / "mpi"), winner_row(dir.path / "local"));
    // The report's 3D view: the start and the winner side by side (their confirmation runs).
    const std::string md = read_file(dir.path / "local" / "optimise" / "report.md");
    EXPECT_NE(md.find("## The start and the winner in 3D"), std::string::npos) << md;
    const std::string html = read_file(dir.path / "local" / "optimise" / "report.html");
    EXPECT_EQ(html.find("<!-- 3D view: variants -->"), std::string::npos) << "the marker is replaced by the view";
    EXPECT_NE(html.find("<div class=\"pv\" data-part=\"rod\">"), std::string::npos);
    EXPECT_NE(html.find("confirm-start"), std::string::npos);
}

}  // namespace
}  // namespace optimise_job_cases
}  // namespace peensim::testing
