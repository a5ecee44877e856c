// The smoothed columns of `peensim analyze` (app/analysis/map_smoothing.h) on a short rod run: written to
// the triangle table and the ParaView file with their radius, the radius chosen as documented (3
// dents at the run's mean normal speed; the scene's output.smoothing_radius; --smoothing-radius),
// and a bad radius refused with the option's name.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/analysis/analyze_job.h"
#include "app/run/run_job.h"
#include "contact/dent.h"
#include "geometry/mesh_loader.h"
#include "support/csv_columns.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using peensim::testing::TempDir;
using namespace peensim;

namespace {

RunOptions rod_run(const fs::path& dir, std::vector<std::string> extra = {}) {
    RunOptions o;
    o.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml";
    o.output_dir = dir.string();
    o.overrides = {"process.duration=0.05"};
    o.overrides.insert(o.overrides.end(), extra.begin(), extra.end());
    o.progress = false;
    o.analyze = false;
    return o;
}

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

}  // namespace

TEST(AnalyzeSmoothing, WritesTheSmoothedFieldsWithTheirRadius) {
    TempDir dir;
    std::ostringstream out, err;
    ASSERT_EQ(run_job(rod_run(dir.path), out, err), kExitOk) << err.str();
    std::ostringstream aout;
    ASSERT_EQ(analyze_job(dir.path.string(), aout, err), kExitOk) << err.str();
    const auto t = peensim::testing::read_csv_columns(dir.path / "analysis" / "rod_triangles.csv");
    for (const char* column : {"impacts_per_mm2_s_smoothed", "impacts_smoothed_rel_error", "mean_vn_mps_smoothed",
                               "energy_J_per_m2_smoothed", "coverage_smoothed", "smoothing_radius_mm"})
        ASSERT_TRUE(t.count(column)) << column;
    // The default radius: 3 dents (eq. 10) of 2 mm steel shot in copper (70 MPa) at the rod's mean
    // normal speed in summary.json, widened to hold 25 impacts at the rod's mean density.
    std::ifstream summary(dir.path / "summary.json");
    const auto j = nlohmann::json::parse(summary);
    const double mean = j["normal_speed"][0]["mean_normal_speed_mps"].get<double>();
    const auto impacts = j["normal_speed"][0]["count"].get<double>();
    const TriangleMesh rod = load_mesh(std::string(PEENSIM_SOURCE_DIR) + "/assets/rod.stl", 1e-3);
    double area = 0.0;  // m2
    for (std::size_t k = 0; k < rod.triangle_count(); ++k)
        area += 0.5 * (rod.corner(k, 1) - rod.corner(k, 0)).cross(rod.corner(k, 2) - rod.corner(k, 0)).norm();
    const double dents_mm = 3.0 * dent_diameter(2e-3, 7800.0, mean, 70e6) * 1e3;
    const double noise_mm = std::sqrt(25.0 * 9.0 / (5.0 * std::numbers::pi * impacts / area)) * 1e3;
    const double radius_mm = std::max(dents_mm, noise_mm);
    for (double r : t.at("smoothing_radius_mm")) ASSERT_NEAR(r, radius_mm, 1e-5 * radius_mm);
    EXPECT_NE(aout.str().find("rod: maps smoothed over"), std::string::npos) << aout.str();
    EXPECT_NE(aout.str().find("3 dents of"), std::string::npos) << aout.str();
    if (noise_mm > dents_mm) {
        EXPECT_NE(aout.str().find("widened from"), std::string::npos) << aout.str();
    }
    // Every triangle of the rod has surface within the radius: a density everywhere, and where
    // it is positive a mean speed and a noise figure; the smoothed coverage is a fraction.
    const auto& density = t.at("impacts_per_mm2_s_smoothed");
    std::size_t hit = 0;
    for (std::size_t k = 0; k < density.size(); ++k) {
        ASSERT_TRUE(std::isfinite(density[k])) << "triangle " << k;
        ASSERT_GE(density[k], 0.0);
        if (density[k] > 0.0) {
            ++hit;
            EXPECT_TRUE(std::isfinite(t.at("mean_vn_mps_smoothed")[k]));
            EXPECT_GT(t.at("impacts_smoothed_rel_error")[k], 0.0);
        }
        EXPECT_GE(t.at("coverage_smoothed")[k], 0.0);
        EXPECT_LE(t.at("coverage_smoothed")[k], 1.0);
    }
    EXPECT_GT(hit, 0u);
    // The ParaView file holds them as cell arrays.
    const std::string vtp = read_text(dir.path / "analysis" / "rod.vtp");
    for (const char* name :
         {"impacts_per_mm2_s_smoothed", "mean_vn_mps_smoothed", "energy_J_per_m2_smoothed", "coverage_smoothed", "smoothing_radius_mm"})
        EXPECT_NE(vtp.find(std::string("Name=\"") + name + "\""), std::string::npos) << name;
}

TEST(AnalyzeSmoothing, TheRadiusComesFromTheOptionThenTheScene) {
    TempDir dir;
    std::ostringstream out, err;
    ASSERT_EQ(run_job(rod_run(dir.path, {"output.smoothing_radius=2 mm"}), out, err), kExitOk) << err.str();
    ASSERT_EQ(analyze_job(dir.path.string(), out, err), kExitOk) << err.str();
    EXPECT_DOUBLE_EQ(peensim::testing::read_csv_columns(dir.path / "analysis" / "rod_triangles.csv").at("smoothing_radius_mm").front(),
                     2.0);
    std::ostringstream aout;
    ASSERT_EQ(analyze_job(dir.path.string(), aout, err, {.smoothing_radius = "1.5 mm"}), kExitOk) << err.str();
    EXPECT_DOUBLE_EQ(peensim::testing::read_csv_columns(dir.path / "analysis" / "rod_triangles.csv").at("smoothing_radius_mm").front(),
                     1.5);
    EXPECT_NE(aout.str().find("set by --smoothing-radius"), std::string::npos) << aout.str();
    for (const char* bad : {"-1 mm", "2 kg", "5 m", "wide"}) {
        std::ostringstream e;
        EXPECT_EQ(analyze_job(dir.path.string(), out, e, {.smoothing_radius = bad}), kExitInputError) << bad;
        EXPECT_NE(e.str().find("--smoothing-radius"), std::string::npos) << e.str();
    }
}
