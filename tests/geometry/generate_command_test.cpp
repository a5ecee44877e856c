// `peensim generate` through the real binary: a mesh is written and reported, bad arguments
// exit with 2 and name the problem, and assets/regenerate.sh reproduces the shipped assets.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "geometry/mesh_checks.h"
#include "geometry/mesh_loader.h"

namespace peensim {
namespace {

namespace fs = std::filesystem;

class GeometryGenerateCommand : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("peensim-generate-" + std::to_string(::getpid()) + "-" + info->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Runs a shell command line, returns its exit code; its stdout+stderr land in output().
    int run(const std::string& command) {
        const std::string log = (dir_ / "log.txt").string();
        const int status = std::system((command + " > '" + log + "' 2>&1").c_str());
        std::ifstream in(log);
        std::stringstream text;
        text << in.rdbuf();
        output_ = text.str();
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    int generate(const std::string& args) { return run(std::string("'") + PEENSIM_BINARY + "' generate " + args); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    const std::string& output() const { return output_; }

    fs::path dir_;
    std::string output_;
};

TEST_F(GeometryGenerateCommand, WritesACylinderAndReportsIt) {
    const std::string file = path("disk.stl");
    ASSERT_EQ(generate("cylinder '" + file + "' --radius-mm 29.9 --height-mm 10 --center-z-mm -5 --segments 32 --cap-rings 2"), 0)
        << output();
    // 32 x 2 on the wall, 32 x (2 x 2 - 1) on each two-ring cap.
    EXPECT_NE(output().find("wrote " + file + ": 256 triangles"), std::string::npos) << output();
    EXPECT_NE(output().find("closed"), std::string::npos);
    const TriangleMesh m = load_mesh(file, 1e-3);
    EXPECT_TRUE(is_closed(m));
    EXPECT_NEAR(bounds(m).min_m.z(), -0.010, 1e-9);
    EXPECT_NEAR(bounds(m).max_m.z(), 0.0, 1e-9);
    EXPECT_NEAR(bounds(m).max_m.x(), 0.0299, 1e-9);
}

TEST_F(GeometryGenerateCommand, GearHonoursTheTriangleTarget) {
    const std::string file = path("gear.stl");
    ASSERT_EQ(generate("gear '" + file + "' --module-mm 1 --teeth 30 --face-width-mm 4 --bore-radius-mm 3 --axis z --triangles 3000"), 0)
        << output();
    const TriangleMesh m = load_mesh(file, 1e-3);
    EXPECT_TRUE(is_closed(m));
    EXPECT_NEAR(static_cast<double>(m.triangle_count()), 3000.0, 300.0);
    EXPECT_NEAR(bounds(m).max_m.z(), 0.002, 1e-9);
    EXPECT_NEAR(bounds(m).max_m.x(), 0.016, 1e-9);  // tip radius (30 + 2) / 2 mm, tooth 0 on +x
}

TEST_F(GeometryGenerateCommand, BadArgumentsExitWithTwoAndSayWhy) {
    const std::string file = path("bad.stl");
    EXPECT_EQ(generate("sphere '" + file + "'"), 2);
    EXPECT_NE(output().find("unknown shape 'sphere'"), std::string::npos) << output();
    EXPECT_EQ(generate("cylinder '" + file + "' --height-mm 3"), 2);
    EXPECT_NE(output().find("--radius-mm is required"), std::string::npos) << output();
    EXPECT_EQ(generate("cylinder '" + file + "' --radius-mm 3 --height-mm 3 --colour red"), 2);
    EXPECT_NE(output().find("unknown key --colour"), std::string::npos) << output();
    EXPECT_EQ(generate("cylinder '" + file + "' --radius-mm 3mm --height-mm 3"), 2);
    EXPECT_NE(output().find("--radius-mm: expected a number, got '3mm'"), std::string::npos) << output();
    EXPECT_EQ(generate("box '" + file + "' --size-x-mm 1 --size-y-mm 1 --size-z-mm 1 --open-face -w"), 2);
    EXPECT_NE(output().find("--open-face"), std::string::npos) << output();
    EXPECT_EQ(generate("gear '" + file + "' --module-mm 2 --teeth 20 --face-width-mm 10 --bore-radius-mm 5 --addendum-coefficient 3"), 2);
    EXPECT_NE(output().find("pointed"), std::string::npos) << output();
    EXPECT_EQ(generate(""), 2);
    EXPECT_FALSE(fs::exists(file));
    EXPECT_EQ(generate("--help"), 0);
    EXPECT_NE(output().find("--bore-radius-mm"), std::string::npos);
}

TEST_F(GeometryGenerateCommand, UnwritableOutputExitsWithOne) {
    EXPECT_EQ(generate("box '" + path("missing/dir/box.stl") + "' --size-x-mm 1 --size-y-mm 1 --size-z-mm 1"), 1);
    EXPECT_NE(output().find("missing/dir/box.stl"), std::string::npos) << output();
}

TEST_F(GeometryGenerateCommand, RegenerateScriptReproducesTheShippedAssets) {
    const std::string source = PEENSIM_SOURCE_DIR;
    ASSERT_EQ(run("PEENSIM='" + std::string(PEENSIM_BINARY) + "' PEENSIM_ASSETS_DIR='" + dir_.string() + "' '" + source +
                  "/assets/regenerate.sh'"),
              0)
        << output();
    for (const char* name :
         {"rod-chamber.stl", "rod-sonotrode.stl", "rod.stl", "gear-chamber.stl", "gear-sonotrode.stl", "gear.stl", "axle.stl"}) {
        SCOPED_TRACE(name);
        const TriangleMesh fresh = load_mesh(path(name), 1e-3);
        const TriangleMesh shipped = load_mesh(source + "/assets/" + name, 1e-3);
        ASSERT_EQ(fresh.triangle_count(), shipped.triangle_count());
        double worst = 0.0;
        for (std::size_t t = 0; t < fresh.triangle_count(); ++t) {
            for (int k = 0; k < 3; ++k) worst = std::max(worst, (fresh.corner(t, k) - shipped.corner(t, k)).norm());
        }
        EXPECT_LT(worst, 1e-9);  // m; float32 in mm rounds at ~1e-9 m
    }
}

}  // namespace
}  // namespace peensim
