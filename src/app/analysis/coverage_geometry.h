// What the coverage of each logged part needs before any dent lands: its coverage map, every
// sample's reach and regions (sample classes), and the area out of the shot's reach. They depend
// on the assembly and the shot alone, and on the shipped gear cost about as much as its 5 s of
// stepping (a reach probe is a distance query to every component), so a run computes them once,
// on the cores it leaves idle while it steps, and hands them to its coverage watch and its analysis;
// before, each of those built the shot's cavity and probed the reach again after the run.
//
// The same figures whoever computes them, on any number of threads: the cavity is the one shot
// placement built (ShotCavity(model, Random(model.seed)), the first to draw from that generator,
// as the analysis builds its own), and the passes merge their chunks in order (parallel_chunks.h).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "analysis/coverage_map.h"
#include "analysis/coverage_progress.h"
#include "analysis/regions.h"
#include "analysis/sample_classes.h"
#include "analysis/unreachable_area.h"
#include "model/model.h"
#include "model/shot_cavity.h"
#include "scene/scene_description.h"

namespace peensim {

// The yield stress (Pa) of component ci's material, or 0 (no coverage: no dents).
double part_yield_stress(const SceneDescription& scene, std::size_t ci);

// One logged part's: absent (map null) when its material has no yield stress (no dents).
struct PartCoverageGeometry {
    RegionSet regions;  // the scene's regions of the part
    std::unique_ptr<CoverageMap> map;
    SampleClasses classes;
    UnreachableFindings unreachable;
    // How a cache folder served it (coverage_geometry_cache.h), for the run's messages: "" without
    // one; else "reused from FILE", "kept in FILE", or why it could be neither.
    std::string cache_note;
};

class CoverageGeometry {
public:
    // The logged parts of `model`. cavity: the shot placement's (null: built here when the model
    // has a sonotrode). background_threads: computed from now on a thread of its own, its passes
    // on that many threads (the cores a run leaves idle); 0: when first asked for, on this one.
    // regions: per component, the region sets the setup check built of these meshes (those not
    // given are built here). cache_dir: a folder the runs of a sweep share (coverage_geometry_cache.h):
    // each part's sample classes and area out of reach are read from there when an earlier run
    // computed them for the same assembly and shot, else computed and kept there ("": neither).
    CoverageGeometry(std::shared_ptr<const Model> model, std::unique_ptr<ShotCavity> cavity, unsigned background_threads,
                     std::vector<std::optional<RegionSet>> regions = {}, std::string cache_dir = {});
    // Stops the thread between chunks of its work (an interrupted run does not wait for it) and
    // joins it.
    ~CoverageGeometry();
    CoverageGeometry(const CoverageGeometry&) = delete;
    CoverageGeometry& operator=(const CoverageGeometry&) = delete;

    // Component ci's (nullptr when it is not logged or has no yield stress). Waits for the thread,
    // which from then on uses every core (whoever waits has given up its own); rethrows what the
    // computation threw.
    const PartCoverageGeometry* part(std::size_t ci);

    const std::shared_ptr<const Model>& model() const { return model_; }

private:
    void compute();
    void wait();

    std::shared_ptr<const Model> model_;
    std::unique_ptr<ShotCavity> cavity_;  // freed once the parts are computed
    std::vector<std::optional<RegionSet>> given_regions_;
    std::string cache_dir_;
    std::vector<std::unique_ptr<PartCoverageGeometry>> parts_;
    std::atomic<bool> cancel_{false};
    std::atomic<unsigned> threads_;  // of the thread's passes (0: every core)
    std::mutex mutex_;
    std::condition_variable done_changed_;
    bool done_ = false;
    std::exception_ptr failure_;
    std::thread thread_;
};

// Component ci's coverage, counting from no dent towards `target` (0..1]: null when the geometry
// has none for it.
std::unique_ptr<CoverageProgress> part_coverage(CoverageGeometry& geometry, std::size_t ci, double target);

}  // namespace peensim
