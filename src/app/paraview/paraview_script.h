// The ParaView script of a run: DIR/analysis/open_in_paraview.py, written by `peensim analyze`,
// opens everything the run and its analysis wrote for ParaView in two views side by side:
//
//   process: the assembly coloured by role (chamber semi-transparent), each logged part coloured
//            by its coverage over time, the shot series as spheres of their size coloured by speed;
//   results: each logged part coloured by impacts per mm2 per s, its impact points by normal speed.
//
// Moving components, and the parts' files (in their own frames), are posed at the animation's time
// from the motion their assembly block carries, so the series play together. Run it with
// `paraview --script=DIR/analysis/open_in_paraview.py`, or headless
// `pvbatch DIR/analysis/open_in_paraview.py --screenshot view.png [--time T]`; `--describe` prints
// what each item holds at that time. Files it names that are missing are skipped.
#pragma once

#include <filesystem>
#include <vector>

#include "app/component_analysis.h"
#include "scene/scene_description.h"

namespace peensim {

inline constexpr const char* kParaviewScriptFileName = "open_in_paraview.py";

// Writes DIR/analysis/open_in_paraview.py for the logged components `parts` (atomically).
// run_duration_s: the run's simulated time (s), the poses' time range; window: what the analysis
// took of it (the impact fields' rates are per its length).
// Written into write_dir (the analysis being written), for the run's analysis/ folder once complete.
void write_paraview_script(const std::filesystem::path& run_dir, const std::filesystem::path& write_dir, const SceneDescription& scene,
                           double fastest_source_m_per_s, const std::vector<ComponentAnalysis>& parts, double run_duration_s,
                           const AnalysisWindow& window);

}  // namespace peensim
