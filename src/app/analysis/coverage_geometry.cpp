#include "app/analysis/coverage_geometry.h"

#include <cstdio>
#include <utility>

#include "analysis/coverage_progress.h"
#include "analysis/part_coverage.h"
#include "analysis/regions.h"
#include "app/analysis/coverage_geometry_cache.h"
#include "common/parallel_chunks.h"
#include "common/random.h"
#include "model/facet_reach.h"
#include "scene/shot_mix.h"

namespace peensim {

double part_yield_stress(const SceneDescription& scene, std::size_t ci) {
    for (const MaterialDesc& m : scene.materials)
        if (m.name == scene.components[ci].material) return m.yield_stress_pa.value_or(0.0);
    return 0.0;
}

CoverageGeometry::CoverageGeometry(std::shared_ptr<const Model> model, std::unique_ptr<ShotCavity> cavity, unsigned background_threads,
                                   std::vector<std::optional<RegionSet>> regions, std::string cache_dir)
    : model_(std::move(model)),
      cavity_(std::move(cavity)),
      given_regions_(std::move(regions)),
      cache_dir_(std::move(cache_dir)),
      threads_(background_threads) {
    parts_.resize(model_->components.size());
    if (background_threads == 0) return;
    thread_ = std::thread([this] {
        // On the cores the run leaves idle only, at the run's own priority: the run's pace (its
        // wall time per simulated second, which the report extrapolates) stays its own, and a run
        // stopped while other processes keep the cores busy is not kept waiting for it. (At
        // SCHED_IDLE it took no time from the run, but a killed sweep's run waited seconds for a
        // starved thread to reach the end of its chunk.)
        chunk_threads_here = &threads_;
        chunk_cancel = &cancel_;
        std::exception_ptr failure;
        try {
            compute();
        } catch (const ChunksCancelled&) {
        } catch (...) {
            failure = std::current_exception();
        }
        const std::lock_guard<std::mutex> lock(mutex_);
        failure_ = failure;
        done_ = true;
        done_changed_.notify_all();
    });
}

CoverageGeometry::~CoverageGeometry() {
    cancel_ = true;
    if (thread_.joinable()) thread_.join();
}

void CoverageGeometry::compute() {
    const Model& model = *model_;
    const SceneDescription& scene = model.description;
    // Built when a part is computed here (none when the cache holds every part).
    const auto cavity = [&]() -> ShotCavity* {
        if (!cavity_ && model.sonotrode >= 0) {
            Random rng(model.seed);
            cavity_ = std::make_unique<ShotCavity>(model, rng);
        }
        return cavity_.get();
    };
    for (std::size_t ci = 0; ci < scene.components.size(); ++ci) {
        throw_if_chunks_cancelled();
        const double yield = part_yield_stress(scene, ci);
        if (!is_logged(scene, scene.components[ci]) || !(yield > 0.0)) continue;
        const TriangleMesh& mesh = *model.components[ci].mesh;
        auto part = std::make_unique<PartCoverageGeometry>();
        part->map =
            part_coverage_map(mesh, smallest_diameter_m(scene.shot), largest_diameter_m(scene.shot), scene.shot.density_kg_per_m3, yield);
        if (ci < given_regions_.size() && given_regions_[ci])
            part->regions = std::move(*given_regions_[ci]);
        else
            part->regions = RegionSet(mesh, scene.components[ci].regions);
        const RegionSet& regions = part->regions;
        std::uint64_t key = 0;
        std::optional<CoverageGeometryLock> lock;
        bool cached = !cache_dir_.empty();
        if (cached) {
            try {
                key = coverage_geometry_key(model, ci, yield);
            } catch (const std::exception& e) {  // the binary cannot be read: no key, no cache
                part->cache_note = std::string("not kept: ") + e.what();
                cached = false;
            }
        }
        if (cached) {
            std::string why;
            // Read it if an earlier run kept it; else wait for a run computing it now, and read it
            // then; else compute it here, the others waiting.
            bool found = load_coverage_geometry(cache_dir_, key, mesh, regions, part->classes, part->unreachable, why);
            if (!found) {
                lock.emplace(cache_dir_, key, [] { throw_if_chunks_cancelled(); });
                found = load_coverage_geometry(cache_dir_, key, mesh, regions, part->classes, part->unreachable, why);
            }
            // How long this run waited for another computing it, if at all (the notes say why a
            // run took longer).
            const auto waited = [&lock](const char* format) {
                char text[96];
                std::snprintf(text, sizeof text, format, lock->waited_s());
                return std::string(text);
            };
            if (found) {
                part->cache_note = "reused from " + coverage_geometry_file(cache_dir_, key);
                if (lock && lock->waited_s() > 0.0) part->cache_note += waited(" (after %.1f s waiting for the run that computed it)");
                parts_[ci] = std::move(part);
                continue;
            }
            if (lock && lock->gave_up()) part->cache_note = waited("another run held it for %.0f s: computed here; ");
            if (!why.empty()) part->cache_note += "computed again (" + why + "); ";
        }
        const ReachTest reach = reach_test(model, ci, cavity());
        const double R = model.min_shot_radius_m;  // the smallest shot of a mix reaches furthest
        part->classes = SampleClasses(*part->map, mesh, regions, reach, R, R / kReachProbesPerRadius);
        throw_if_chunks_cancelled();
        part->unreachable = find_unreachable_area(*part->map, part->classes, regions, reach, R);
        if (cached) {
            try {
                store_coverage_geometry(cache_dir_, key, part->classes, part->unreachable);
                part->cache_note += "kept in " + coverage_geometry_file(cache_dir_, key);
            } catch (const std::exception& e) {
                part->cache_note += std::string("not kept: ") + e.what();
            }
        }
        parts_[ci] = std::move(part);
    }
    cavity_.reset();  // up to ~8 M cells, of no more use
    given_regions_.clear();
}

void CoverageGeometry::wait() {
    if (!thread_.joinable()) {
        // Computed here, once.
        if (!done_) {
            compute();
            done_ = true;
        }
        return;
    }
    threads_ = 0;  // the waiting thread's core is free: the passes take it at their next chunk
    std::unique_lock<std::mutex> lock(mutex_);
    done_changed_.wait(lock, [this] { return done_; });
    if (failure_) std::rethrow_exception(failure_);
}

const PartCoverageGeometry* CoverageGeometry::part(std::size_t ci) {
    wait();
    return ci < parts_.size() ? parts_[ci].get() : nullptr;
}

std::unique_ptr<CoverageProgress> part_coverage(CoverageGeometry& geometry, std::size_t ci, double target) {
    const PartCoverageGeometry* part = geometry.part(ci);
    if (part == nullptr) return nullptr;
    return std::make_unique<CoverageProgress>(std::make_unique<CoverageMap>(*part->map), part->classes, target);
}

}  // namespace peensim
