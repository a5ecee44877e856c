// The smoothed per-area fields of `peensim analyze` (analysis/surface_smoothing.h) for one logged
// component: which radius, and the calls the job makes while it streams the log and at its end.
//
// The radius R: `analyze --smoothing-radius`, else the scene's `output.smoothing_radius`, else the
// larger of two lengths. The dent scale: kSmoothingDents dent diameters (eq. 10) of an impact at
// the component's mean normal speed (the shot's diameter, a mix's mean by count) when its material
// has a yield stress, else kFallbackSmoothingRadius: a dent is the smallest feature an impact
// leaves. The noise scale: the radius whose kernel holds kKernelImpacts impacts at the component's
// mean density (impacts / area, 5/9 of the kernel's disc counting, surface_smoothing.h), so that
// the map's noise is about 1/sqrt(kKernelImpacts) where the density is average. Measured on the
// default 5 s gear run (7243 impacts on 4900 mm2): 3 dents are 0.52 mm and leave the density +-100 %
// (speckle again); the noise scale is 2.9 mm. A longer run sharpens the map down to the dent scale.
// Both figures come from the run's summary.json (mean normal speed and impact count per
// component), read before the log is streamed; an analysis of a window of the run
// (`analyze --from --to`) expects its share of the impacts.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "scene/scene_description.h"

namespace peensim {

struct ComponentAnalysis;
struct ImpactRow;

inline constexpr double kSmoothingDents = 3.0;            // default R: at least this many dent diameters
inline constexpr double kFallbackSmoothingRadius = 1e-3;  // m, the dent scale without a dent size
inline constexpr double kKernelImpacts = 25.0;  // default R: at least this many impacts in the kernel at the mean density (+-20 %)

struct SmoothingChoice {
    double radius_m = kFallbackSmoothingRadius;  // m
    std::string basis;                           // why this radius, for the user ("3 dents of 0.2 mm at 1.6 m/s (eq. 10)")
};

// The radius of `analyze --smoothing-radius TEXT` (m; nullopt for an empty text). Throws InputError
// naming the option for a text that is not a length in [1 um, 1 m].
std::optional<double> smoothing_radius_option(const std::string& text);

// run_dir: the run's directory (its summary.json gives the mean normal speed and the impacts);
// area_m2: the component's surface area (m2); window_share: the share of the run's time analysed
// (0..1], the share of its impacts the maps will hold.
SmoothingChoice choose_smoothing_radius(const SceneDescription& scene, const ComponentDesc& component, const std::filesystem::path& run_dir,
                                        double area_m2, std::optional<double> command_line_radius_m, double window_share = 1.0);

// Sets up the component's smoothing (its mesh and fields made) at the radius chosen as above;
// option_text: `--smoothing-radius`'s text, or empty.
void start_smoothing(ComponentAnalysis& a, const SceneDescription& scene, const ComponentDesc& component,
                     const std::filesystem::path& run_dir, const std::string& option_text, double window_share = 1.0);
// One impact row on triangle t of the component's mesh (from TriangleFields::add), of a shot of
// mass_kg (kg).
void smooth_impact(ComponentAnalysis& a, const ImpactRow& row, int t, double mass_kg);
// After the log: the coverage map's samples, then the smoothed fields at every triangle.
void finish_smoothing(ComponentAnalysis& a);
// One line for the user: the radius, why, and the median noise of the smoothed impact density.
std::string smoothing_note(const ComponentAnalysis& a);

}  // namespace peensim
