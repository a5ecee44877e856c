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
#include "analysis/avrami.h"
#include "analysis/coverage_map.h"
#include "analysis/impact_histograms.h"
#include "analysis/jet_stream.h"
#include "analysis/regions.h"
#include "analysis/surface_smoothing.h"
#include "analysis/triangle_fields.h"
#include "geometry/triangle_mesh.h"
#include "output/vtp_writer.h"
#include "scene/scene_description.h"

namespace peensim {

// Time batches the run is cut into for batch means (a confidence interval from one run).
inline constexpr int kFigureBatches = 10;

// The Almen side of a component with role almen.
struct AlmenAnalysis {
    std::unique_ptr<AlmenDose> dose;
    std::optional<AlmenCalibration> calibration;  // from the scene; empty = dose only
    std::vector<AlmenDosePoint> curve;            // dose vs time, sampled like the coverage curve
};

struct ComponentAnalysis {
    std::string name;
    ComponentRole role = ComponentRole::part;
    std::unique_ptr<TriangleMesh> mesh;
    std::unique_ptr<TriangleFields> fields;
    std::unique_ptr<CoverageMap> coverage;  // empty if the material has no yield stress
    double yield_stress_pa = 0.0;           // Pa (0: none)
    ImpactHistograms histograms;
    std::uint64_t impacts = 0;
    double speed_sum = 0.0;  // m/s, summed over impacts
    double dent_sum = 0.0;   // m, summed over impacts
    std::vector<CoveragePoint> curve;
    // The per-area fields smoothed over a radius of the surface (app/map_smoothing.h): the
    // binning while the log streams, why its radius, and the sums at each triangle at the end.
    std::unique_ptr<SurfaceSmoothing> smoothing;
    std::string smoothing_basis;
    std::vector<SmoothedSums> smoothed;
    std::unique_ptr<ImpactPointsVtpWriter> points;    // the impacts, for ParaView
    std::vector<Region> regions;                      // the scene's regions of the component
    std::vector<ImpactHistograms> region_histograms;  // per region, same order
    // The regions holding triangle t: region_index_[region_start_[t] .. region_start_[t + 1]).
    std::vector<std::uint32_t> region_start;
    std::vector<std::uint32_t> region_index;
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
