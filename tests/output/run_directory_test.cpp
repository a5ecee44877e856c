// One run per output directory, one run's outputs in it. Users found two runs started into the
// same directory mixing their impacts.csv rows, and a fresh run killed early leaving the previous
// run's summary.json (finished: true) and analysis/ beside its own scene; and a run whose disk
// filled while it wrote its final summary (impacts.csv already renamed) could not be resumed.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/checkpoint/checkpoint.h"
#include "app/run/run_job.h"
#include "common/input_error.h"
#include "output/impact_csv_writer.h"
#include "output/run_directory.h"
#include "support/files.h"
#include "support/run_in_process.h"
#include "support/temp_dir.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

TEST(RunDirectory, ASecondRunIntoTheSameDirectoryIsRefusedNamingTheFirst) {
    TempDir dir;
    {
        const RunDirectoryLock first(dir.path.string());
        try {
            const RunDirectoryLock second(dir.path.string());
            ADD_FAILURE() << "a second lock was granted";
        } catch (const InputError& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find("in use by another peensim run (pid " + std::to_string(::getpid()) + ", started "), std::string::npos) << m;
            EXPECT_NE(m.find("choose another directory with -o"), std::string::npos) << m;
        }
    }
    // Released with its holder.
    EXPECT_NO_THROW(RunDirectoryLock again(dir.path.string()));
}

TEST(RunDirectory, ClearingRemovesOnlyWhatARunWrites) {
    TempDir dir;
    for (const char* name : {"summary.json", "impacts.csv", "checkpoint.bin", "notes.txt"}) std::ofstream(dir.path / name) << "x";
    fs::create_directories(dir.path / "analysis" / "deep");
    std::ofstream(dir.path / "analysis" / "deep" / "rod_triangles.csv") << "x";
    const std::vector<std::string> removed = clear_previous_outputs(dir.path.string());
    EXPECT_EQ(removed.size(), 4u);
    EXPECT_FALSE(fs::exists(dir.path / "summary.json"));
    EXPECT_FALSE(fs::exists(dir.path / "analysis"));
    EXPECT_TRUE(fs::exists(dir.path / "notes.txt"));
}

TestSceneSpec small_spec() {
    TestSceneSpec spec = thrown_shot_scene(16, 0.05);
    spec.log = {"sonotrode"};
    return spec;
}

int run(const TestScene& scene, const std::string& dir, bool resume, std::optional<std::uint64_t> stop_after,
        std::string* err_text = nullptr) {
    const InProcessResult r = run_in_process({scene.scene_path(), dir, resume, false, stop_after, {}});
    if (err_text) *err_text = r.err;
    return r.code;
}

TEST(RunDirectory, AFreshRunKilledEarlyLeavesNothingOfThePreviousRun) {
    const TestScene scene(small_spec());
    const fs::path dir = scene.make_subdirectory("out");
    std::ofstream(dir / "summary.json") << "{\"finished\": true, \"from\": \"an old run\"}";
    fs::create_directories(dir / "analysis");
    std::ofstream(dir / "analysis" / "report.md") << "old";
    std::ofstream(dir / "notes.txt") << "mine";
    std::string err;
    ASSERT_EQ(run(scene, dir.string(), false, 20, &err), kExitInterrupted) << err;
    EXPECT_NE(err.find("note: replaced a previous run's outputs in"), std::string::npos) << err;
    EXPECT_EQ(read_file(dir / "summary.json").find("an old run"), std::string::npos);
    EXPECT_NE(read_file(dir / "summary.json").find("\"finished\": false"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "analysis"));
    EXPECT_EQ(read_file(dir / "notes.txt"), "mine");
}

TEST(RunDirectory, ARunThatFailedAfterRenamingItsImpactsResumes) {
    const TestScene scene(small_spec());
    const fs::path whole = scene.make_subdirectory("whole"), parts = scene.make_subdirectory("parts");
    ASSERT_EQ(run(scene, whole.string(), false, {}), kExitOk);
    ASSERT_EQ(run(scene, parts.string(), false, 200), kExitInterrupted);
    // As if the run had finished its impacts (renamed) and then failed writing its summary.
    fs::rename(parts / kImpactCsvPartialFileName, parts / kImpactCsvFileName);
    std::string err;
    ASSERT_EQ(run(scene, parts.string(), true, {}, &err), kExitOk) << err;
    EXPECT_TRUE(read_file(whole / kImpactCsvFileName) == read_file(parts / kImpactCsvFileName));
    EXPECT_FALSE(fs::exists(parts / kImpactCsvPartialFileName));
}

}  // namespace
}  // namespace peensim::testing
