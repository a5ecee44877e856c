// A run whose disk fills while it streams its impacts stops with an error, and --resume (once there
// is room) continues it to the very bytes of an uninterrupted run. The full disk is a file size
// limit on the child run (`ulimit -f`: writes past it fail with EFBIG, as they fail with ENOSPC on a
// full disk). Before, a run that failed before its first periodic checkpoint (60 s of wall time)
// left nothing to resume from: a run now checkpoints its start. An analysis that fills the disk
// fails as cleanly.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "output/impact_csv_writer.h"
#include "support/files.h"
#include "support/temp_dir.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

int exit_code_of(const std::string& command) {
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(DiskFull, ARunThatFillsTheDiskResumesToTheUninterruptedBytes) {
    TempDir dir;
    const std::string scene = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml";
    const std::string args = " --quiet --no-analyze --no-render --set process.duration=0.5";
    const fs::path whole = dir.path / "whole", parts = dir.path / "parts";
    ASSERT_EQ(exit_code_of(std::string(PEENSIM_BINARY) + " run " + scene + " -o " + whole.string() + args), 0);
    ASSERT_GT(fs::file_size(whole / kImpactCsvFileName), 100000u);  // well past the limit below
    // 40 KiB per file: the checkpoint (~26 KB) fits, the impacts do not.
    const std::string limited = "bash -c \"ulimit -f 40; trap '' XFSZ; exec " + std::string(PEENSIM_BINARY) + " run " + scene + " -o " +
                                parts.string() + args + "\" 2> " + (dir.path / "err.txt").string();
    EXPECT_EQ(exit_code_of(limited), 1);
    const std::string err = read_file(dir.path / "err.txt");
    EXPECT_NE(err.find("File too large"), std::string::npos) << err;
    // The command to go on: every --set, and the options a resumed run does not keep.
    EXPECT_NE(err.find("--resume --set 'process.duration=0.5' --no-analyze --no-render continues from its last checkpoint"),
              std::string::npos)
        << err;
    ASSERT_EQ(exit_code_of(std::string(PEENSIM_BINARY) + " run " + scene + " -o " + parts.string() + args + " --resume"), 0);
    EXPECT_TRUE(read_file(whole / kImpactCsvFileName) == read_file(parts / kImpactCsvFileName));
}

// The analysis writes its files beside each other on several threads (the coverage series, the
// per-triangle tables, the report): one that fails fails the analysis with its file named, and no
// half-written analysis/ takes the place of a whole one, nor stays beside it.
TEST(DiskFull, AnAnalysisThatFillsTheDiskFailsNamingItsFileAndLeavesNoAnalysis) {
    TempDir dir;
    const std::string scene = std::string(PEENSIM_SOURCE_DIR) + "/scenes/gear.yaml";
    const fs::path run = dir.path / "run";
    ASSERT_EQ(exit_code_of(std::string(PEENSIM_BINARY) + " run " + scene + " -o " + run.string() +
                           " --quiet --no-analyze --no-render --set process.duration=0.5"),
              0);
    // 200 KiB per file: the log is read, a coverage step of the 5k-triangle gear (~260 KB) is not written.
    const std::string limited = "bash -c \"ulimit -f 200; trap '' XFSZ; exec " + std::string(PEENSIM_BINARY) + " analyze " + run.string() +
                                "\" > /dev/null 2> " + (dir.path / "err.txt").string();
    EXPECT_EQ(exit_code_of(limited), 1);
    const std::string err = read_file(dir.path / "err.txt");
    EXPECT_NE(err.find("File too large"), std::string::npos) << err;
    EXPECT_NE(err.find("analysis.partial/"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(run / "analysis"));
    EXPECT_FALSE(fs::exists(run / "analysis.partial"));  // nor half of one
    // With room again, the same command analyses the run whole.
    ASSERT_EQ(exit_code_of(std::string(PEENSIM_BINARY) + " analyze " + run.string() + " > /dev/null"), 0);
    EXPECT_TRUE(fs::exists(run / "analysis" / "gear_coverage_series.pvd"));
    EXPECT_FALSE(fs::exists(run / "analysis.partial"));
}

}  // namespace
}  // namespace peensim::testing
