// PNG plots of an analysis (coverage vs time, histograms), drawn by gnuplot if it is installed.
// gnuplot is looked up on PATH at run time, not linked: peensim builds and analyses without it,
// and the plots are then simply missing (with a note saying how to get them).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace peensim {

// Terminal size of every plot, pixels.
inline constexpr int kPlotWidthPx = 800;
inline constexpr int kPlotHeightPx = 600;

// The note left when gnuplot is not on PATH.
inline constexpr std::string_view kNoGnuplotNote = "gnuplot not found: no PNG plots (apt-get install gnuplot-nox)";

// For every component c in `components`, reads `analysis_dir/<c>_coverage.csv` and
// `analysis_dir/<c>_histograms.csv` (those that exist), writes a gnuplot script next to each
// (`<c>_coverage.gp`, `<c>_histograms.gp`, kept so users can edit and rerun them from the analysis
// dir: `gnuplot <c>_coverage.gp`) and runs it, giving `<c>_coverage.png` (coverage in % vs time)
// and `<c>_histograms.png` (normal speed, impact angle, dent diameter), and where their CSV exists
// `<c>_regions.png` (impacts per area and mean normal speed per region) and `<c>_almen.png` (dose
// and calibrated arc height vs time). Each PNG is rendered to
// `<png>.tmp` and renamed, so a PNG is either complete or absent.
// Returns the paths of the PNGs written. `note` is empty when all went well; otherwise it says
// why plots are missing (gnuplot not found, or gnuplot's own error message).
// Throws std::runtime_error only if a script cannot be written.
// target_coverage (0..1): the dashed line on the coverage plot, the report's target.
std::vector<std::string> write_analysis_plots(const std::string& analysis_dir, const std::vector<std::string>& components,
                                              double target_coverage, std::string& note);

// Writes `dir/stem.gp` and renders `dir/stem.png` with it (through `stem.png.tmp`, renamed: complete
// or absent). Returns "" when done, else why not (gnuplot missing, or its messages). The script
// writes to the file named by the variable `out`, which this sets (`set output out`).
std::string plot_with_gnuplot(const std::string& dir, const std::string& stem, const std::string& script);
std::string gnuplot_string(const std::string& s);  // `s` as a gnuplot single-quoted string
std::string gnuplot_text(const std::string& s);    // `s` escaped for gnuplot's enhanced text

}  // namespace peensim
