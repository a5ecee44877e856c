// What `peensim analyze` accumulates for one logged component while it streams the impact log,
// shared by the job (which fills it) and the writers of tables and of the report (which read it).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/almen.h"
#include "analysis/almen_model.h"
#include "analysis/avrami.h"
#include "analysis/coverage_map.h"
#include "analysis/coverage_outlook.h"
#include "analysis/impact_histograms.h"
#include "analysis/jet_stream.h"
#include "analysis/region_stats.h"
#include "analysis/regions.h"
#include "analysis/surface_smoothing.h"
#include "analysis/triangle_fields.h"
#include "geometry/triangle_mesh.h"
#include "output/vtp_writer.h"
#include "scene/scene_description.h"

namespace peensim {

// What of the log an analysis takes (`peensim analyze --from --to --min-speed --target`).
struct AnalysisWindow {
    double from_s = 0.0;                               // s: impacts before are left out (a start-up transient)
    double to_s = 0.0;                                 // s: and after (the run's end by default)
    double min_speed_m_per_s = 0.0;                    // m/s: slower impacts are left out
    double target_coverage = 0.98;                     // the share of the area below it is reported
    double length_s() const { return to_s - from_s; }  // s, the analysed time: rates are per it
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
    std::unique_ptr<CoverageMap> coverage;  // empty if the material has no yield stress
    double yield_stress_pa = 0.0;           // Pa (0: none)
    ImpactHistograms histograms;
    std::uint64_t impacts = 0;
    double speed_sum = 0.0;                                 // m/s, summed over impacts
    double dent_sum = 0.0;                                  // m, summed over impacts
    std::vector<CoveragePoint> curve;                       // coverage of the peened area vs time since the window opened
    // The per-area fields smoothed over a radius of the surface (app/map_smoothing.h): the
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
    // Per triangle: the share of it a shot can reach (model/facet_reach.h), and the weight coverage
    // gives its area: reach x (1 - its share in excluded regions).
    std::vector<double> reach;
    std::vector<double> peened;
    std::array<double, kFigureBatches> batch_dent_area_m2{};  // m2, dents delivered on the peened area per batch
    // Filled once the log has been read.
    CoverageOutlook outlook;                       // the peened area's
    std::vector<CoverageOutlook> region_outlooks;  // per region
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
