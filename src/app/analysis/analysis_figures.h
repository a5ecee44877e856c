// The figures of an analysis as data: `analysis/figures.json`, what the report's tables show, for
// programs (a sweep's comparison, a notebook) rather than readers. Per logged component: impacts,
// their rate and mean normal speed, the mean dent, coverage, the time to the target (whole peened
// area, per region, everywhere) with its status and interval, uniformity, the share below the
// target, the Almen dose, per region its rate, speed and coverage, and the impact rate and mean
// normal speed of each tenth of the run (batch means: a confidence interval from one run).
#pragma once

#include <string>
#include <vector>

#include "app/component_analysis.h"

namespace peensim {

// The JSON text of the figures (rates per the window's length).
std::string analysis_figures_json(const std::vector<ComponentAnalysis>& parts, const AnalysisWindow& window);

}  // namespace peensim
