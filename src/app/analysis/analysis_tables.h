// The files of `peensim analyze` for one component (CSV tables and the ParaView mesh), written
// atomically into the analysis directory. Column names carry their units.
#pragma once

#include <filesystem>

#include "app/component_analysis.h"

namespace peensim {

// <c>_triangles.csv and <c>.vtp, the per-triangle files: of the maps (the smoothing done), not of
// the forecast, so they can be written while it runs. Rates are per the window's length.
void write_triangle_tables(const std::filesystem::path& analysis_dir, const ComponentAnalysis& c, const AnalysisWindow& window);

// <c>_histograms.csv, and those that apply of <c>_coverage.csv, <c>_regions.csv (with the
// forecast), <c>_region_coverage.csv, <c>_almen.csv and <c>_jet.csv. Rates are per the window's
// length; times are the log's.
void write_component_tables(const std::filesystem::path& analysis_dir, const ComponentAnalysis& c, const AnalysisWindow& window);

}  // namespace peensim
