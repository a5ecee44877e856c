// What `peensim analyze` accumulates for one logged component while it streams the impact log,
// shared by the job (which fills it) and the writers of tables and of the report (which read it).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/almen.h"
#include "analysis/almen_model.h"
#include "analysis/coverage_forecast.h"
#include "analysis/coverage_progress.h"
#include "analysis/impact_histograms.h"
#include "analysis/jet_stream.h"
#include "analysis/region_stats.h"
#include "analysis/regions.h"
#include "analysis/surface_smoothing.h"
#include "analysis/triangle_fields.h"
#include "analysis/unreachable_area.h"
#include "geometry/triangle_mesh.h"
#include "output/vtp_writer.h"
#include "scene/scene_description.h"

namespace peensim {

// SAE J2277's "full" coverage: 98 % of the area dented.
inline constexpr double kFullCoverage = 0.98;

// What of the log an analysis takes (`peensim analyze --from --to --min-speed --target`).
struct AnalysisWindow {
    double from_s = 0.0;                               // s: impacts before are left out (a start-up transient)
    double to_s = 0.0;                                 // s: and after (the run's end by default)
    double min_speed_m_per_s = 0.0;                    // m/s: slower impacts are left out
    double target_coverage = kFullCoverage;            // what the times to the target and the share below it are of
    double length_s() const { return to_s - from_s; }  // s, the analysed time: rates are per it
    // A rotating part is analysed over whole turns: a part of a turn favours the side that faced
    // the sonotrode in it.
    double turn_s = 0.0;      // s, the logged part's turn (0: nothing logged rotates)
    double asked_to_s = 0.0;  // s, the end asked for (the log's end by default) before whole turns
    bool to_given = false;    // --to was given: kept as asked, warned about if not whole turns
    // The run peened until every area of every logged part reached a target at least this one
    // (--until-coverage) and ended there: that end is its answer, kept, part of a turn and all.
    bool ends_at_target = false;
    // A run until coverage of some areas only (process.until_coverage_of) is still cut to whole
    // turns, for the other areas' forecasts; the watched areas it saw reach the target after the
    // cut ("part" or "part/region", s), whose times the analysis takes from it.
    std::vector<std::pair<std::string, double>> seen_reached_after;
    double turns() const { return turn_s > 0.0 ? length_s() / turn_s : 0.0; }
    bool shorter_than_a_turn() const { return turn_s > 0.0 && turns() < 1.0 - 1e-9; }
};

// The Almen side of a component with role almen.
struct AlmenAnalysis {
    std::unique_ptr<AlmenDose> dose;
    std::optional<AlmenCalibration> calibration;  // the dose model's, from the scene; empty = none
    std::optional<AlmenModelCalibration> model;   // the predictive model's, from the scene; empty = none
    double shot_density_kg_per_m3 = 0.0;          // kg/m3
    double yield_stress_pa = 0.0;                 // Pa, the strip material's (0: none, so no dents)
    std::vector<AlmenDosePoint> curve;            // dose and dents vs time, sampled like the coverage curve
};

struct ComponentAnalysis {
    std::string name;
    std::size_t index = 0;  // in the scene's (and the model's) components
    ComponentRole role = ComponentRole::part;
    std::shared_ptr<const TriangleMesh> mesh;  // the compiled model's (component frame, m)
    std::unique_ptr<TriangleFields> fields;
    // Coverage of the peened area as the dents land (empty if the material has no yield stress).
    std::unique_ptr<CoverageProgress> coverage;
    double yield_stress_pa = 0.0;  // Pa (0: none)
    ImpactHistograms histograms;
    std::uint64_t impacts = 0;
    double speed_sum = 0.0;            // m/s, summed over impacts
    double dent_sum = 0.0;             // m, summed over impacts
    std::vector<CoveragePoint> curve;  // coverage of the peened area vs time since the window opened
    // The per-area fields smoothed over a radius of the surface (app/analysis/map_smoothing.h): the
    // binning while the log streams, why its radius, and the sums at each triangle at the end.
    std::unique_ptr<SurfaceSmoothing> smoothing;
    std::string smoothing_basis;
    std::vector<SmoothedSums> smoothed;
    std::unique_ptr<ImpactPointsVtpWriter> points;          // the impacts, for ParaView
    RegionSet regions;                                      // the scene's regions of the component
    std::vector<RegionTally> region_tallies;                // per region: what its impacts brought
    std::vector<ImpactHistograms> region_histograms;        // per region, same order
    std::vector<std::vector<CoveragePoint>> region_curves;  // per region: coverage vs time since the window opened
    std::vector<std::uint32_t> impact_regions;              // the regions of the impact being added (reused)
    // Per triangle: the share of its samples a shot can reach (sample_classes.h).
    std::vector<double> reach;
    // The area out of reach, per region, and the shot that would reach it (unreachable_area.h).
    UnreachableFindings unreachable;
    // The forecast's impacts (on faces, and on edges, which dent a strip along them:
    // coverage_forecast.h) and, once the log has been read, the forecast.
    std::vector<ForecastImpact> forecast_impacts;
    CoverageForecast forecast;
    std::optional<AlmenAnalysis> almen;
    // Scenes with nozzles: how the jet arrives (analysis/jet_stream.h). The jet's axis in the
    // component's frame, and whether the normal-speed share means anything (one nozzle, a static
    // component: a turning part's facets face the jet at every angle).
    std::optional<JetStreamStats> jet;
    Vec3 jet_axis = -Vec3::UnitZ();
    bool jet_normal_meaningful = false;
    // A shot mix's log: the impacts of each size (in the order first met; a log of one size keeps none).
    struct SizeTally {
        double diameter_m = 0.0;  // m
        std::uint64_t impacts = 0;
        double speed_sum = 0.0;  // m/s, summed normal speeds
        double dent_sum = 0.0;   // m, summed dent diameters (with a yield stress)
        double energy_J = 0.0;   // J, 1/2 m v_n^2 summed
    };
    std::vector<SizeTally> sizes;
    // Per batch of the run's time (batch means, analysis_figures.h): impacts and their summed normal speed.
    std::array<std::uint64_t, kFigureBatches> batch_impacts{};
    std::array<double, kFigureBatches> batch_speed_sum{};  // m/s
};

}  // namespace peensim
