// An optimisation's report (DIR/optimise/): report.md and report.html (the winner with its
// predicted and confirmed objective and intervals, how much better than the start, the command
// that reproduces it, a plot per variable of the model through the winner with the runs, the
// search's progress, every evaluation; in the page, the start and the winner side by side in 3D),
// and evaluations.csv (a row per setting).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/optimise/bayes_search.h"
#include "app/optimise/optimise_settings.h"
#include "app/optimise/study_file.h"
#include "app/sweep/sweep_compare.h"
#include "app/sweep/sweep_plan.h"

namespace peensim {

struct OptimiseResult {
    const Study& study;
    std::string title;                          // the scene's name
    const std::vector<StudySetting>& settings;  // every setting evaluated, settings[0] the start
    SettingFigures figures;                     // theirs, as settings
    std::optional<SearchModel> model;           // fitted on every complete setting
    std::vector<SearchPoint> points;
    std::vector<std::size_t> point_setting;
    std::size_t best = 0;         // the winner (a setting)
    std::uint64_t base_seed = 0;  // the scene's process.seed: the search's first replicates
    int budget = 0;
    std::string stopped_because;
    std::size_t failed_runs = 0;
    std::optional<SweepPlan> confirm_plan;    // the independent runs: confirm-start, confirm-<winner>
    std::optional<SettingFigures> confirmed;  // their figures
};

struct OptimiseReportFiles {
    std::string summary;  // the lines the command prints: the winner and its figures
    bool plots = false;
};

OptimiseReportFiles write_optimise_report(const OptimiseResult& result, const std::string& dir);

}  // namespace peensim
