// `peensim analyze OUTDIR` (also run at the end of `peensim run` unless --no-analyze): streams a
// run's impact log once and writes, into OUTDIR/analysis/, per logged component: per-triangle
// fields (CSV), coverage (SAE J2277, dents from eq. 10) vs time with its Avrami fit, histograms of
// normal speed, impact angle and dent diameter, and report.md putting the numbers on one page.
#pragma once

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

namespace peensim {

struct Model;
class CoverageGeometry;

// What of the log to analyse, and the target the report measures coverage against.
struct AnalyzeOptions {
    double from_s = 0.0;             // s: impacts before are left out (drop a start-up transient)
    std::optional<double> to_s{};    // s: and after (default: the end of the log)
    double min_speed_m_per_s = 0.0;  // m/s: slower impacts are left out (too slow to dent)
    // The coverage the report measures against (0..1]: empty for the run's own (its scene's
    // process.until_coverage), else 98 % (SAE J2277's "full" coverage).
    std::optional<double> target_coverage = std::nullopt;
    // The maps' smoothing radius as the user wrote it ("2 mm", `--smoothing-radius`): empty for the
    // scene's `output.smoothing_radius` or the default (app/analysis/map_smoothing.h).
    std::string smoothing_radius;
    // The run's own model, when the run analyses itself: its meshes loaded, BVHs built and checks
    // done once, not again (on a 500k-triangle part about 1.5 s). Used only if the directory's
    // scene.resolved.yaml resolves to the same text; else the scene is compiled afresh.
    std::shared_ptr<const Model> model{};
    // The run's coverage geometry of that model (coverage_geometry.h), computed while it stepped:
    // used with the model.
    std::shared_ptr<CoverageGeometry> geometry{};
    // A folder of coverage geometries to reuse and keep (coverage_geometry_cache.h): a sweep's
    // runs share one. "": computed here, kept nowhere.
    std::string geometry_cache_dir{};
};

int analyze_job(const std::string& output_dir, std::ostream& out, std::ostream& err, const AnalyzeOptions& options = {});

// The same, with errors thrown (InputError for a bad scene, std::runtime_error for a directory
// that is not a run's) instead of reported: for a caller with exceptions of its own (Python).
void analyze_run(const std::string& output_dir, std::ostream& out, std::ostream& err, const AnalyzeOptions& options = {});

}  // namespace peensim
