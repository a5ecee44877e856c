// Scenes the engine cannot run end in exit code 2 with a message that says what and where, never a
// crash: more shot than fit on the sonotrode, and chambers that do not close around it.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>

#include "app/run/run_job.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

struct RunResult {
    int code = 0;
    std::string err;
};

RunResult run(const TestScene& scene) {
    RunOptions o;
    o.scene_path = scene.scene_path();
    o.output_dir = scene.make_subdirectory("out");
    o.progress = false;
    std::ostringstream out, err;
    RunResult r;
    r.code = run_job(o, out, err);
    r.err = err.str();
    return r;
}

// 1-based number of the first line of `text` that starts with `prefix` (after indentation), or 0.
int line_of(const std::string& text, const std::string& prefix) {
    std::istringstream in(text);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n)
        if (line.find_first_not_of(' ') != std::string::npos && line.substr(line.find_first_not_of(' ')).rfind(prefix, 0) == 0) return n;
    return 0;
}

// The point "near (x, y, z) mm" of a closure message, in mm.
bool escape_point(const std::string& message, double& x, double& y, double& z) {
    const std::regex near(R"(near \(([-0-9.e+]+), ([-0-9.e+]+), ([-0-9.e+]+)\) mm)");
    std::smatch m;
    if (!std::regex_search(message, m, near)) return false;
    x = std::stod(m[1]), y = std::stod(m[2]), z = std::stod(m[3]);
    return true;
}

TEST(EngineBadScene, MoreShotThanFitOnTheSonotrode) {
    // 100000 shot of 2 mm on a 20 x 20 mm plate (about 100 fit per layer).
    TestSceneSpec spec;
    spec.shot_count = 100000;
    const TestScene scene(spec);
    const RunResult r = run(scene);
    std::cout << "[ bad scene] " << r.err;
    EXPECT_EQ(r.code, kExitInputError);
    EXPECT_NE(r.err.find(scene.scene_path()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("shot.count"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("100000"), std::string::npos) << r.err;
    // The line: that of `count:` (the shot map's first key) or of `shot:`.
    const int count_line = line_of(scene.yaml(), "count:"), shot_line = line_of(scene.yaml(), "shot:");
    ASSERT_GT(count_line, 0);
    const bool names_line = r.err.find(scene.scene_path() + ":" + std::to_string(count_line) + ":") != std::string::npos ||
                            r.err.find(scene.scene_path() + ":" + std::to_string(shot_line) + ":") != std::string::npos;
    EXPECT_TRUE(names_line) << "expected line " << count_line << " (or " << shot_line << ") in: " << r.err;
}

TEST(EngineBadScene, ChamberMissingASideWall) {
    // The chamber's +x wall (at x = 10 mm) is left out: the shot could leave through it.
    TestSceneSpec spec;
    spec.chamber_missing_side_wall = true;
    const TestScene scene(spec);
    const RunResult r = run(scene);
    std::cout << "[ bad scene] " << r.err;
    EXPECT_EQ(r.code, kExitInputError);
    EXPECT_NE(r.err.find(scene.scene_path()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("not closed"), std::string::npos) << r.err;
    double x = 0, y = 0, z = 0;
    ASSERT_TRUE(escape_point(r.err, x, y, z)) << r.err;
    // Where: beyond the missing wall (x > 10 mm), not through the closed sides or the ceiling.
    EXPECT_GT(x, 10.0) << r.err;
    EXPECT_LT(std::abs(y), 10.0 + 2.0) << r.err;
    EXPECT_LT(z, 20.0) << r.err;
}

TEST(EngineBadScene, SonotrodeMuchSmallerThanTheOpening) {
    // A 10 x 10 mm plate in a 20 x 20 mm opening: a 5 mm gap all around, down past the plate.
    TestSceneSpec spec;
    spec.plate_scale = 0.5;
    const TestScene scene(spec);
    const RunResult r = run(scene);
    std::cout << "[ bad scene] " << r.err;
    EXPECT_EQ(r.code, kExitInputError);
    EXPECT_NE(r.err.find(scene.scene_path()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("not closed"), std::string::npos) << r.err;
    double x = 0, y = 0, z = 0;
    ASSERT_TRUE(escape_point(r.err, x, y, z)) << r.err;
    // Where: out through the open bottom of the chamber (below the plate's bottom face at z = -5 mm).
    EXPECT_LT(z, -5.0) << r.err;
}

}  // namespace
}  // namespace peensim::testing
