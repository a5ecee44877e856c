// Benchmark of `peensim analyze` on a big impact log: N synthetic impacts (default 10 million) on
// the shipped gear, then analyze_job on them (first a tenth of them, then all); prints rows/s, wall
// time, peak memory and the gear's row of the analysis table (the coverage reached).
//   peensim_analysis_bench [N]        (run from the repository root; needs ~200 bytes of /tmp per impact)
// The run directory is a real one (scene.resolved.yaml from a 0.01 s run of scenes/gear.yaml) whose
// impact log is replaced by the synthetic one; it is deleted at the end.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "app/analysis/analyze_job.h"
#include "app/run/run_job.h"
#include "geometry/mesh_loader.h"
#include "output/impact_csv_writer.h"
#include "output/peak_memory.h"
#include "scene/scene_parser.h"

namespace fs = std::filesystem;
using namespace peensim;

namespace {

constexpr std::uint64_t kDefaultImpacts = 10'000'000;
constexpr double kSimulatedTimeS = 10.0;     // s, the span the synthetic impact times cover
constexpr double kMaxNormalSpeed = 5.0;      // m/s, normal speeds are uniform in [0, this]
constexpr double kMaxTangentialSpeed = 2.0;  // m/s, tangential speeds are uniform in [0, this]
constexpr double kRestitution = 0.6;         // -, rebound normal speed / approach normal speed
constexpr std::uint64_t kSeed = 20261122;

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Writes `n` impacts spread uniformly over the triangles' list (not their area) of `mesh`, at
// uniform random points inside them, times increasing over kSimulatedTimeS.
void write_synthetic_impacts(const fs::path& dir, const SceneDescription& scene, const std::string& part, std::uint64_t n) {
    std::vector<std::string> names;
    int part_index = -1;
    for (const ComponentDesc& c : scene.components) {
        if (c.name == part) part_index = static_cast<int>(names.size());
        names.push_back(c.name);
    }
    const ComponentDesc& desc = scene.components[static_cast<std::size_t>(part_index)];
    const TriangleMesh mesh = load_mesh(desc.mesh_path, desc.mesh_unit_m);

    std::mt19937_64 rng(kSeed);
    std::uniform_int_distribution<std::size_t> pick(0, mesh.triangle_count() - 1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    ImpactCsvWriter writer(dir.string(), names);
    ImpactRecord r;
    r.component = part_index;
    for (std::uint64_t i = 0; i < n; ++i) {
        const std::size_t t = pick(rng);
        const Vec3 &a = mesh.corner(t, 0), &b = mesh.corner(t, 1), &c = mesh.corner(t, 2);
        double u = unit(rng), v = unit(rng);
        if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;  // fold into the triangle: uniform over it
        const Vec3 normal = (b - a).cross(c - a).normalized();
        const Vec3 tangent = (b - a).normalized();
        r.time_s = kSimulatedTimeS * static_cast<double>(i) / static_cast<double>(n);
        r.shot = static_cast<std::int32_t>(i % 1000);
        r.triangle = mesh.source_facet.empty() ? static_cast<std::int32_t>(t) : mesh.source_facet[t];
        r.point_m = a + u * (b - a) + v * (c - a);
        r.vn_in_m_per_s = kMaxNormalSpeed * unit(rng);
        r.vt_in_m_per_s = kMaxTangentialSpeed * unit(rng);
        r.v_in_m_per_s = -r.vn_in_m_per_s * normal + r.vt_in_m_per_s * tangent;
        r.vn_out_m_per_s = kRestitution * r.vn_in_m_per_s;
        r.v_out_m_per_s = r.vn_out_m_per_s * normal + r.vt_in_m_per_s * tangent;
        writer.write(r);
    }
    writer.finish();
    std::ofstream(dir / "summary.json") << "{\"simulated_time_s\": " << kSimulatedTimeS << "}\n";
}

}  // namespace

int main(int argc, char** argv) {
    const std::uint64_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : kDefaultImpacts;
    if (n == 0) {
        std::cerr << "usage: peensim_analysis_bench [impacts > 0]\n";
        return 2;
    }
    char tmpl[] = "/tmp/peensim-analysis-bench-XXXXXX";
    if (!mkdtemp(tmpl)) {
        std::perror("mkdtemp");
        return 1;
    }
    const fs::path dir(tmpl);
    int status = 0;
    try {
        RunOptions o;
        o.scene_path = "scenes/gear.yaml";
        o.output_dir = dir.string();
        o.overrides = {"process.duration=0.01"};
        o.progress = false;
        o.analyze = false;
        std::ostringstream run_out, run_err;
        if (run_job(o, run_out, run_err) != kExitOk)
            throw std::runtime_error("the gear run failed (run from the repository root?): " + run_err.str());
        const SceneDescription scene = parse_scene_file((dir / "scene.resolved.yaml").string());

        // A tenth of the impacts first, then all of them: the same peak memory shows that the
        // analysis streams (peak_resident_bytes is the process's high-water mark, so the second
        // figure is the larger of the two runs).
        for (const std::uint64_t count : {std::max<std::uint64_t>(n / 10, 1), n}) {
            const auto t_write = std::chrono::steady_clock::now();
            write_synthetic_impacts(dir, scene, "gear", count);
            const double write_s = seconds_since(t_write);
            const auto log_bytes = fs::file_size(dir / kImpactCsvFileName);

            const auto t_analyze = std::chrono::steady_clock::now();
            std::ostringstream out, err;
            if (analyze_job(dir.string(), out, err) != kExitOk) throw std::runtime_error("analyze failed: " + err.str());
            const double analyze_s = seconds_since(t_analyze);
            std::string gear_row;
            std::istringstream table(out.str());
            for (std::string line; std::getline(table, line);)
                if (line.starts_with("| gear ")) gear_row = line;

            std::cout << "# peensim analyze benchmark: " << count << " synthetic impacts on the gear (scenes/gear.yaml)\n"
                      << "impact log: " << log_bytes / 1e6 << " MB, written in " << write_s << " s\n"
                      << "analyze: " << analyze_s << " s wall, " << static_cast<double>(count) / analyze_s / 1e6
                      << " M rows/s, peak memory " << static_cast<double>(peak_resident_bytes()) / 1e6
                      << " MB (whole process, high-water mark so far)\n"
                      << "result: " << gear_row << "\n";
        }
    } catch (const std::exception& e) {
        std::cerr << "peensim_analysis_bench: " << e.what() << "\n";
        status = 1;
    }
    std::error_code ec;
    fs::remove_all(dir, ec);
    return status;
}
