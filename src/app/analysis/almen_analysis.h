// What `peensim analyze` does for an Almen strip (role almen), kept in one place: the strip's state
// while the impact log streams (dose, dents), its table `<strip>_almen.csv`, its report section and
// its figures in figures.json. The physics is in analysis/almen.h (dose, the two-constant dose
// model) and analysis/almen_model.h (the predictive model calibrated on a measured curve).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/component_analysis.h"
#include "scene/scene_description.h"

namespace peensim {

// The strip's analysis state. mesh: the strip in its own frame; shot_mass_kg: the mean shot's;
// yield_stress_pa: the strip material's (0: none, so no dents and no prediction).
// Throws InputError when the face normal finds no face.
AlmenAnalysis almen_analysis_of(const ComponentDesc& strip, const TriangleMesh& mesh, double shot_mass_kg, double shot_density_kg_per_m3,
                                double yield_stress_pa);

// One impact of the log on the strip (triangle index, or < 0 off the mesh): its dose and, on the
// peened face with a yield stress, its dent (eq. 10 with this impact's shot diameter).
void add_almen_impact(AlmenAnalysis& a, int triangle, double vn_m_per_s, double shot_diameter_m, double shot_mass_kg);

// The dose and dents so far, as a point of the curve at `time_s`.
void sample_almen(AlmenAnalysis& a, double time_s);

// `<strip>_almen.csv` (times of the log: the window's start plus the curve's): time_s, dose_J_per_m2, arc_height_mm (the dose model, when
// calibrated), dent_area_ratio (with a yield stress), predicted_arc_height_mm (the predictive model, when calibrated).
void write_almen_csv(const std::filesystem::path& path, const AlmenAnalysis& a, double window_start_s);

// report.md's sections of every strip among `parts`.
std::string almen_report_sections(const std::vector<ComponentAnalysis>& parts, double duration_s);

// figures.json's Almen figures of a strip, added to its component object.
void add_almen_figures(nlohmann::ordered_json& component, const AlmenAnalysis& a);

// "0.2435 mm = 0.009587 in = 9.587 thou (0.0096A)": an intensity in m in the units engineers
// quote, with the J442 strip letter when given ("" = none).
std::string almen_intensity_text(double intensity_m, const std::string& strip);
// "0.0096A" (in, 4 decimals, with the strip letter), "" without a strip letter.
std::string almen_intensity_label(double intensity_m, const std::string& strip);

}  // namespace peensim
