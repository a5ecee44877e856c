#include "app/paraview/paraview_coverage_series.h"

#include <cstdio>

#include "output/vtk_collection.h"
#include "output/vtp_writer.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

std::string series_name(const ComponentAnalysis& a) { return a.name + "_coverage_series"; }

std::string step_file(const ComponentAnalysis& a, int j) {
    char number[16];
    std::snprintf(number, sizeof number, "%04d", j);
    return series_name(a) + "/" + a.name + "_coverage_" + number + ".vtp";
}

}  // namespace

CoverageSeries::CoverageSeries(const fs::path& analysis_dir, const std::vector<ComponentAnalysis>& parts, const AnalysisWindow& window,
                               int steps)
    : dir_(analysis_dir), parts_(parts), from_s_(window.from_s), to_s_(window.to_s), steps_(steps) {
    for (const ComponentAnalysis& a : parts_) {
        fs::remove_all(dir_ / series_name(a));  // a series of another N would leave its extra steps
        fs::remove(dir_ / (series_name(a) + ".pvd"));
        if (a.coverage && steps_ > 0) fs::create_directories(dir_ / series_name(a));
    }
}

void CoverageSeries::before(double time_s) {
    while (steps_ > 0 && next_ <= steps_ && step_time(next_) <= time_s) write_step(next_++);
}

void CoverageSeries::finish() {
    if (steps_ <= 0) return;
    // No impact comes after these steps: one copy of the coverage serves them all. A 500k-triangle
    // part's step is ~26 MB, and a short run's steps all fall here: written while the forecast and
    // the smoothing go on instead of before them.
    const int first = next_;
    next_ = steps_ + 1;
    writing_ = std::async(std::launch::async, [this, first, earlier = std::move(writing_),
                                               coverage = first <= steps_ ? coverage_now() : Coverages{}]() mutable {
        if (earlier.valid()) earlier.get();
        for (int j = first; j <= steps_; ++j) write_files(j, coverage);
        write_pvds();
    });
}

void CoverageSeries::wait() {
    if (writing_.valid()) writing_.get();
}

CoverageSeries::Coverages CoverageSeries::coverage_now() const {
    Coverages coverage(parts_.size());
    for (std::size_t p = 0; p < parts_.size(); ++p) {
        const ComponentAnalysis& a = parts_[p];
        if (!a.coverage) continue;
        coverage[p].resize(a.mesh->triangle_count());
        for (std::size_t t = 0; t < coverage[p].size(); ++t) coverage[p][t] = a.coverage->shown_triangle_coverage(t);
    }
    return coverage;
}

void CoverageSeries::write_step(int j) {
    // The coverage now, written on the writer's thread while the log streams on; one step in
    // flight at a time.
    Coverages coverage = coverage_now();
    wait();
    writing_ = std::async(std::launch::async, [this, j, coverage = std::move(coverage)] { write_files(j, coverage); });
}

void CoverageSeries::write_files(int j, const Coverages& coverage) const {
    for (std::size_t p = 0; p < parts_.size(); ++p) {
        const ComponentAnalysis& a = parts_[p];
        if (!a.coverage) continue;
        const TriangleMesh& mesh = *a.mesh;
        PolyDataLayout layout{mesh.vertices.size(),  PolyDataLayout::Cells::triangles,
                              mesh.triangle_count(), {},
                              {{"coverage"}},        {{"time_s", std::vector<double>{step_time(j)}}}};
        PolyDataWriter out((dir_ / step_file(a, j)).string(), std::move(layout));
        out.add_points(mesh.vertices);
        out.add_triangles(mesh.triangles);
        out.add(std::span<const double>(coverage[p]));
        out.finish();
    }
}

void CoverageSeries::write_pvds() const {
    for (const ComponentAnalysis& a : parts_) {
        if (!a.coverage) continue;
        std::vector<TimeStepFile> files;
        for (int j = 0; j <= steps_; ++j) files.push_back({step_time(j), step_file(a, j)});
        write_pvd((dir_ / (series_name(a) + ".pvd")).string(), files);
    }
}

CoverageSeries::~CoverageSeries() {
    if (writing_.valid()) writing_.wait();  // an analysis that failed: its writer is done before parts_ go
}

}  // namespace peensim
