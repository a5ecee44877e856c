// `peensim run --until-coverage` (scene `process.until_coverage`): keeps the coverage of the logged
// parts as the analysis counts it (app/analysis/coverage_geometry.h), dent by dent as the run logs its
// impacts (in the log's time order, whichever replica made them), and says when every watched area
// reached the target: the run ends at the first restart point after that. Brute force instead of a forecast: the reference every forecast
// is checked against, and the answer for whoever can afford the simulation. A resumed run rebuilds the coverage from its impact log up to
// the checkpoint.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "analysis/coverage_progress.h"
#include "analysis/regions.h"
#include "app/analysis/coverage_geometry.h"
#include "engine/impact_record.h"
#include "model/model.h"

namespace peensim {

// One watched area and when it reached the target.
struct WatchedArea {
    std::string name;           // "part" or "part/region"
    double reached_at_s = 0.0;  // s of simulated time (NaN: not yet)
    double coverage = 0.0;      // 0..1, now
};

class CoverageWatch final {
public:
    // geometry: the run's (its model's description has process.until_coverage set), whose parts'
    // coverage it counts; resume_log: the partial impact log of a resumed run ("" for a fresh
    // one), read up to its end.
    CoverageWatch(CoverageGeometry& geometry, const std::string& resume_log);
    ~CoverageWatch();

    // The dents of impacts logged now, at their times in the log.
    void add(std::span<const ImpactRecord> impacts);
    bool done() const;

    double target() const { return target_; }
    std::vector<WatchedArea> areas() const;
    // The areas process.until_coverage_of names that no shot can reach (no peened area): not
    // waited for ("part/region"). When every named area is such, the constructor throws instead.
    const std::vector<std::string>& out_of_reach() const { return out_of_reach_; }

private:
    struct Part;
    void add_dent(std::size_t component, const Vec3& point_m, double vn_m_per_s, double shot_diameter_m, double time_s);

    const Model& model_;
    double target_ = 0.98;
    std::vector<std::unique_ptr<Part>> parts_;
    std::vector<int> part_of_component_;  // per component: index into parts_ (-1: not watched)
    std::vector<std::string> out_of_reach_;
};

}  // namespace peensim
