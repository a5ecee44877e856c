// The comparison of a sweep's variants (`DIR/sweep/`): one row per variant in comparison.csv and
// report.md. What decides a process comes first: the slowest region's time to the target, the time
// to it everywhere, the uniformity and the share of the area below it; then the whole part's time,
// impact rate, mean and p90 normal speed, coverage, Almen dose and per-region rate, coverage and
// time. Each has its 95 % confidence interval (from the seed replicates with Student's t; with one
// seed, from the run's batch means for rate and speed and from the run's own forecast interval for
// the times and the uniformity), the difference from the baseline variant and a verdict (differs /
// within noise); and a plot per varied field.
#pragma once

#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/sweep/sweep_plan.h"

namespace peensim {

// A figure of a variant: its mean over the variant's runs and the half-width of its 95 % interval
// (empty: no interval, one run without batch means).
struct SweepFigure {
    std::optional<double> mean;
    std::optional<double> ci95;
    std::string missing;  // why there is no mean ("too short: run 600 s"); "" = none given
};

// mean +- t_{0.975, n-1} sd / sqrt(n) of `values` (empty ci95 for fewer than two).
SweepFigure mean_with_ci95(const std::vector<double>& values);

// The difference a - b and whether it exceeds the combined half-width sqrt(ci_a^2 + ci_b^2).
struct SweepDifference {
    std::optional<double> delta;
    std::string verdict;  // "differs", "within noise", "-" (no interval on one side)
};
SweepDifference compare_figures(const SweepFigure& a, const SweepFigure& b);

// Every variant's figures as comparison.csv has them, by its column name (the figure's half-width
// in SweepFigure::ci95): impact_rate_per_s, ..., time_to_target_everywhere_s, ..., and per region
// region_<name>_impact_rate_per_s, region_<name>_coverage, region_<name>_time_to_target_s.
struct SweepVariantFigures {
    std::size_t runs = 0;  // finished runs read
    std::map<std::string, SweepFigure> figures;
    std::string slowest_region;  // the region slowest in most runs
};
struct SweepFigures {
    std::string component;                      // the logged part read
    double target_coverage = NAN;               // the target the runs' forecasts aim at (0..1)
    std::vector<SweepVariantFigures> variants;  // as plan.variants
};

// Reads every finished run of `plan` (summary.json, analysis/figures.json) for `component` ("" =
// the first logged part); writes nothing.
SweepFigures read_sweep_figures(const SweepPlan& plan, const std::string& component = "");

struct SweepCompareResult {
    std::string component;          // the logged part compared
    std::vector<std::string> pngs;  // plots written
    std::string plot_note;          // why plots are missing ("" = none)
};

// Reads every finished run of `plan` (its summary.json and analysis/figures.json) and writes
// sweep_dir/comparison.csv, sweep_dir/report.md and the plots. baseline: a variant's name ("" =
// the first). Throws std::runtime_error for a baseline the plan does not have.
SweepCompareResult write_sweep_comparison(const SweepPlan& plan, const std::string& sweep_dir, const std::string& baseline,
                                          const std::string& title);

}  // namespace peensim
