// Coverage over time for ParaView (scene `output.coverage_steps`, N; default 10), written by
// `peensim analyze` while it streams the impact log, for every logged component with a coverage
// map (its material has a yield stress):
//
//   DIR/analysis/<part>_coverage_series.pvd                      the time series (open this one)
//   DIR/analysis/<part>_coverage_series/<part>_coverage_<j>.vtp  step j at t_j = from + (to - from) j / N, j = 0..N
//
// from..to is the analysis window (`analyze --from --to`; the whole run by default).
//
// Step j is the part's mesh (component frame, as <part>.vtp) with the cell array `coverage`
// (fraction 0..1 of each triangle inside a dent, from the impacts before t_j) and the field data
// `time_s`. Each step is a whole mesh (a .pvd step cannot share another file's geometry): about
// 52 bytes per triangle (Float64 points, Int64 connectivity), ~16 MB a step for a 300k-triangle part.
#pragma once

#include <filesystem>
#include <future>
#include <string>
#include <vector>

#include "app/component_analysis.h"

namespace peensim {

class CoverageSeries {
public:
    // Clears the series of an earlier analysis. parts: the analysis' components (outlive this);
    // window: the simulated time analysed (s); steps: N (0: no series).
    CoverageSeries(const std::filesystem::path& analysis_dir, const std::vector<ComponentAnalysis>& parts, const AnalysisWindow& window,
                   int steps);
    ~CoverageSeries();
    CoverageSeries(const CoverageSeries&) = delete;
    CoverageSeries& operator=(const CoverageSeries&) = delete;

    // Before the impact at time_s is added: writes every step whose time is not after it.
    void before(double time_s);
    // After the last impact: the steps left (the run's end included) and each part's .pvd, written
    // on the writer's thread while the analysis goes on (they all show the final coverage).
    void finish();
    // Until every file is written; rethrows what the writing threw.
    void wait();

private:
    using Coverages = std::vector<std::vector<double>>;  // per part (empty: no coverage map), per triangle
    double step_time(int j) const { return j == steps_ ? to_s_ : from_s_ + (to_s_ - from_s_) * j / steps_; }
    Coverages coverage_now() const;
    void write_step(int j);
    void write_files(int j, const Coverages& coverage) const;
    void write_pvds() const;

    std::filesystem::path dir_;
    const std::vector<ComponentAnalysis>& parts_;
    double from_s_, to_s_;
    int steps_;
    int next_ = 0;
    std::future<void> writing_;  // the files of the last steps handed to the writer
};

}  // namespace peensim
