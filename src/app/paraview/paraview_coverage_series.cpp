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
        const TriangleMesh& mesh = *a.mesh;
        PolyDataLayout layout{mesh.vertices.size(),  PolyDataLayout::Cells::triangles,
                              mesh.triangle_count(), {},
                              {{"coverage"}},        {{"time_s", std::vector<double>{step_time(j)}}}};
        PolyDataWriter out((dir_ / step_file(a, j)).string(), std::move(layout));
        out.add_points(mesh.vertices);
        for (const auto& tri : mesh.triangles) out.add_triangle(tri);
        for (std::size_t t = 0; t < mesh.triangle_count(); ++t) out.add(a.coverage->shown_triangle_coverage(t));
        out.finish();
    }
}

}  // namespace peensim
