// Determinism of whole runs through run_job: the same scene and seed give a byte-identical
// impacts.csv, another seed a different one, and a run interrupted after K steps (exit 130,
// checkpoint written) and resumed ends with exactly the uninterrupted run's impacts.csv.
// The same-seed / other-seed test runs with each stepping scheme (accuracy.scheme step and event);
// the resume tests run time stepping, and the event-driven scheme in one of its own.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "app/checkpoint/checkpoint.h"
#include "app/run/run_job.h"
#include "output/impact_csv_writer.h"
#include "support/files.h"
#include "support/run_in_process.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

// A small, fast scene: 64 shot of 2 mm thrown up at 1 m/s (and by the 25 um sonotrode) onto a
// static rod 8 mm above the plate, for 0.05 s; impacts on the rod and the sonotrode are logged.
TestSceneSpec small_scene(std::uint64_t seed, std::string scheme = "step") {
    TestSceneSpec spec;
    spec.scheme = std::move(scheme);
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

std::size_t rows(const std::string& csv) { return static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')) - 1; }

int run(const TestScene& scene, const std::string& dir, bool resume = false, std::optional<std::uint64_t> stop_after = {}) {
    const InProcessResult r = run_in_process({scene.scene_path(), dir, resume, true, stop_after, {}});
    EXPECT_TRUE(r.code == kExitOk || r.code == kExitInterrupted) << r.err;
    return r.code;
}

class EngineDeterminismSchemes : public ::testing::TestWithParam<std::string> {};

TEST_P(EngineDeterminismSchemes, SameSeedSameBytesOtherSeedOtherBytes) {
    const TestScene scene(small_scene(1, GetParam()));
    const std::string a = scene.make_subdirectory("a"), b = scene.make_subdirectory("b");
    ASSERT_EQ(run(scene, a), kExitOk);
    ASSERT_EQ(run(scene, b), kExitOk);
    const std::string csv_a = read_file(fs::path(a) / kImpactCsvFileName), csv_b = read_file(fs::path(b) / kImpactCsvFileName);
    std::cout << "[ determin ] " << GetParam() << " scheme: " << rows(csv_a) << " impact rows, " << csv_a.size() << " bytes\n";
    ASSERT_GT(rows(csv_a), 100u);  // enough impacts for the comparison to mean something
    EXPECT_TRUE(csv_a == csv_b) << "two runs of one scene differ";

    const TestScene other(small_scene(2, GetParam()));
    const std::string c = other.make_subdirectory("c");
    ASSERT_EQ(run(other, c), kExitOk);
    const std::string csv_c = read_file(fs::path(c) / kImpactCsvFileName);
    EXPECT_GT(rows(csv_c), 100u);
    EXPECT_FALSE(csv_a == csv_c) << "another seed gave the same impacts";
}

INSTANTIATE_TEST_SUITE_P(Schemes, EngineDeterminismSchemes, ::testing::Values(std::string("step"), std::string("event")),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

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
    std::cout << "[ resume   ] uninterrupted " << rows(expected) << " rows, interrupted at step " << K << " and resumed " << rows(resumed)
              << " rows\n";
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

TEST(EngineDeterminism, EventDrivenRunResumedTwiceEqualsUninterrupted) {
    // The event-driven scheme keeps flights, modes and a neighbour tree besides the state, so it
    // stops (and checkpoints) only at its restart points, every EventStepping::kRestartInterval of
    // simulated time, where it starts afresh from the state alone as a resumed run does. A 0.35 s
    // run interrupted twice (stop requests after 30 units of work: honoured at 0.1 s, then at 0.2 s)
    // and resumed ends with the uninterrupted run's bytes.
    TestSceneSpec spec = small_scene(5, "event");
    spec.duration_s = 0.35;
    const TestScene scene(spec);
    const std::string whole = scene.make_subdirectory("whole"), parts = scene.make_subdirectory("parts");
    ASSERT_EQ(run(scene, whole), kExitOk);
    ASSERT_EQ(run(scene, parts, false, 30), kExitInterrupted);
    const Checkpoint first = load_checkpoint((fs::path(parts) / kCheckpointFileName).string());
    EXPECT_DOUBLE_EQ(first.state.time.seconds(), 0.1);
    ASSERT_EQ(run(scene, parts, true, 30), kExitInterrupted);
    const Checkpoint second = load_checkpoint((fs::path(parts) / kCheckpointFileName).string());
    EXPECT_DOUBLE_EQ(second.state.time.seconds(), 0.2);
    ASSERT_EQ(run(scene, parts, true), kExitOk);
    const std::string expected = read_file(fs::path(whole) / kImpactCsvFileName);
    const std::string resumed = read_file(fs::path(parts) / kImpactCsvFileName);
    std::cout << "[ resume   ] event scheme: uninterrupted " << rows(expected) << " rows, resumed twice " << rows(resumed) << " rows\n";
    ASSERT_GT(rows(expected), 300u);
    EXPECT_TRUE(expected == resumed) << "the resumed event-driven run differs from the uninterrupted one";
}

}  // namespace
}  // namespace peensim::testing
