// Determinism of whole runs through run_job: the same scene and seed give a byte-identical
// impacts.csv, another seed a different one, and a run interrupted after K steps (exit 130,
// checkpoint written) and resumed ends with exactly the uninterrupted run's impacts.csv.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>

#include "app/checkpoint.h"
#include "app/run_job.h"
#include "output/impact_csv_writer.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

// A small, fast scene: 64 shot of 2 mm thrown up at 1 m/s (and by the 25 um sonotrode) onto a
// static rod 8 mm above the plate, for 0.05 s; impacts on the rod and the sonotrode are logged.
TestSceneSpec small_scene(std::uint64_t seed) {
    TestSceneSpec spec;
    spec.shot_count = 64;
    spec.initial_speed_m_per_s = 1.0;
    spec.amplitude_m = 25e-6;
    spec.duration_s = 0.05;
    spec.seed = seed;
    PartSpec rod;
    rod.shape = PartShape::cylinder;
    rod.radius_m = 3e-3;
    rod.length_m = 16e-3;
    rod.axis = Axis::y;
    rod.center_m = Vec3(0.0, 0.0, 8e-3);
    spec.part = rod;
    spec.log = {"part", "sonotrode"};
    return spec;
}

std::string read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t rows(const std::string& csv) { return static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')) - 1; }

int run(const TestScene& scene, const std::string& dir, bool resume = false, std::optional<std::uint64_t> stop_after = {}) {
    RunOptions o;
    o.scene_path = scene.scene_path();
    o.output_dir = dir;
    o.progress = false;
    o.resume = resume;
    o.stop_after_steps = stop_after;
    std::ostringstream out, err;
    const int code = run_job(o, out, err);
    EXPECT_TRUE(code == kExitOk || code == kExitInterrupted) << err.str();
    return code;
}

TEST(EngineDeterminism, SameSeedSameBytesOtherSeedOtherBytes) {
    const TestScene scene(small_scene(1));
    const std::string a = scene.make_subdirectory("a"), b = scene.make_subdirectory("b");
    ASSERT_EQ(run(scene, a), kExitOk);
    ASSERT_EQ(run(scene, b), kExitOk);
    const std::string csv_a = read_file(fs::path(a) / kImpactCsvFileName), csv_b = read_file(fs::path(b) / kImpactCsvFileName);
    std::cout << "[ determin ] " << rows(csv_a) << " impact rows, " << csv_a.size() << " bytes\n";
    ASSERT_GT(rows(csv_a), 100u);  // enough impacts for the comparison to mean something
    EXPECT_TRUE(csv_a == csv_b) << "two runs of one scene differ";

    const TestScene other(small_scene(2));
    const std::string c = other.make_subdirectory("c");
    ASSERT_EQ(run(other, c), kExitOk);
    const std::string csv_c = read_file(fs::path(c) / kImpactCsvFileName);
    EXPECT_GT(rows(csv_c), 100u);
    EXPECT_FALSE(csv_a == csv_c) << "another seed gave the same impacts";
}

TEST(EngineDeterminism, InterruptedAndResumedRunEqualsUninterrupted) {
    const TestScene scene(small_scene(3));
    const std::string whole = scene.make_subdirectory("whole"), parts = scene.make_subdirectory("parts");
    ASSERT_EQ(run(scene, whole), kExitOk);

    constexpr std::uint64_t K = 200;  // steps before the interruption (the run takes ~600)
    ASSERT_EQ(run(scene, parts, false, K), kExitInterrupted);
    EXPECT_TRUE(fs::exists(fs::path(parts) / kCheckpointFileName));
    EXPECT_TRUE(fs::exists(fs::path(parts) / kImpactCsvPartialFileName));
    EXPECT_FALSE(fs::exists(fs::path(parts) / kImpactCsvFileName));  // only a finished run has one
    ASSERT_EQ(run(scene, parts, true), kExitOk);
    EXPECT_FALSE(fs::exists(fs::path(parts) / kCheckpointFileName));

    const std::string expected = read_file(fs::path(whole) / kImpactCsvFileName);
    const std::string resumed = read_file(fs::path(parts) / kImpactCsvFileName);
    std::cout << "[ resume   ] uninterrupted " << rows(expected) << " rows, interrupted at step " << K << " and resumed "
              << rows(resumed) << " rows\n";
    ASSERT_GT(rows(expected), 100u);
    EXPECT_TRUE(expected == resumed) << "the resumed run differs from the uninterrupted one";
}

TEST(EngineDeterminism, ResumedTwiceEqualsUninterrupted) {
    // Two interruptions in a row (the second resume is itself interrupted): still the same bytes.
    const TestScene scene(small_scene(4));
    const std::string whole = scene.make_subdirectory("whole"), parts = scene.make_subdirectory("parts");
    ASSERT_EQ(run(scene, whole), kExitOk);
    ASSERT_EQ(run(scene, parts, false, 150), kExitInterrupted);
    ASSERT_EQ(run(scene, parts, true, 150), kExitInterrupted);
    ASSERT_EQ(run(scene, parts, true), kExitOk);
    EXPECT_TRUE(read_file(fs::path(whole) / kImpactCsvFileName) == read_file(fs::path(parts) / kImpactCsvFileName));
}

}  // namespace
}  // namespace peensim::testing
