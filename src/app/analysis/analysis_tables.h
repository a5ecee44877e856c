// The files of `peensim analyze` for one component (CSV tables and the ParaView mesh), written
// atomically into the analysis directory. Column names carry their units.
#pragma once

#include <filesystem>

#include "app/component_analysis.h"

namespace peensim {

// <c>_triangles.csv, <c>_histograms.csv, <c>.vtp, and those that apply of <c>_coverage.csv,
// <c>_regions.csv, <c>_region_coverage.csv, <c>_almen.csv and <c>_jet.csv. Rates are per the
// window's length; times are the log's.
void write_component_tables(const std::filesystem::path& analysis_dir, const ComponentAnalysis& c, const AnalysisWindow& window);

}  // namespace peensim
