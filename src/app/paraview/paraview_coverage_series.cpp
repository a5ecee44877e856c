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
    while (next_ <= steps_) write_step(next_++);
    wait_for_writer();
    for (const ComponentAnalysis& a : parts_) {
        if (!a.coverage) continue;
        std::vector<TimeStepFile> files;
        for (int j = 0; j <= steps_; ++j) files.push_back({step_time(j), step_file(a, j)});
        write_pvd((dir_ / (series_name(a) + ".pvd")).string(), files);
    }
}

void CoverageSeries::write_step(int j) {
    for (const ComponentAnalysis& a : parts_) {
        if (!a.coverage) continue;
        // The coverage now, written on the writer's thread while the log streams on (a step of a
        // 500k-triangle part is ~20 MB); one step in flight at a time.
        std::vector<double> coverage(a.mesh->triangle_count());
        for (std::size_t t = 0; t < coverage.size(); ++t) coverage[t] = a.coverage->shown_triangle_coverage(t);
        wait_for_writer();
        writing_ = std::async(std::launch::async, [this, &a, j, coverage = std::move(coverage)] {
            const TriangleMesh& mesh = *a.mesh;
            PolyDataLayout layout{mesh.vertices.size(),  PolyDataLayout::Cells::triangles,
                                  mesh.triangle_count(), {},
                                  {{"coverage"}},        {{"time_s", std::vector<double>{step_time(j)}}}};
            PolyDataWriter out((dir_ / step_file(a, j)).string(), std::move(layout));
            out.add_points(mesh.vertices);
            for (const auto& tri : mesh.triangles) out.add_triangle(tri);
            for (const double c : coverage) out.add(c);
            out.finish();
        });
    }
}

void CoverageSeries::wait_for_writer() {
    if (writing_.valid()) writing_.get();
}

CoverageSeries::~CoverageSeries() {
    if (writing_.valid()) writing_.wait();  // an analysis that failed: its writer is done before parts_ go
}

}  // namespace peensim
