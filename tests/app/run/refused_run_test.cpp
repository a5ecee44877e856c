// A fresh run refused at its setup, after its directory was made (its shot do not fit on the
// sonotrode: known only once they are placed), exits 2 at the field and leaves nothing behind: no
// directory it made, and in a directory that was there, none of its outputs (it once left its
// scene.resolved.yaml, and its lock in a directory it made: they read as a run that started).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/exit_codes.h"
#include "support/shell_command.h"
#include "support/temp_dir.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

TEST(RefusedRun, ShotThatDoNotFitLeaveNothingBehind) {
    TempDir dir;
    const auto run = [&](const fs::path& out) {
        return run_shell(std::string("'") + PEENSIM_BINARY + "' run '" + PEENSIM_SOURCE_DIR + "/scenes/rod.yaml' -o '" + out.string() +
                         "' -q --set 'shot.diameter=12 mm' --set 'process.duration=2 ms' 2>&1");
    };
    const ShellResult fresh = run(dir.path / "fresh");
    ASSERT_TRUE(WIFEXITED(fresh.status)) << fresh.output;
    EXPECT_EQ(WEXITSTATUS(fresh.status), kExitInputError) << fresh.output;
    EXPECT_NE(fresh.output.find("rod.yaml:14:1: shot.count: expected at most about"), std::string::npos) << fresh.output;
    EXPECT_FALSE(fs::exists(dir.path / "fresh")) << fresh.output;
    // A directory of the user's: kept, with what was in it, and none of the run's outputs (only
    // the hidden lock file every run leaves in its directory).
    fs::create_directories(dir.path / "mine");
    std::ofstream(dir.path / "mine" / "notes.txt") << "mine\n";
    const ShellResult into = run(dir.path / "mine");
    EXPECT_EQ(WEXITSTATUS(into.status), kExitInputError) << into.output;
    for (const fs::directory_entry& e : fs::directory_iterator(dir.path / "mine"))
        EXPECT_TRUE(e.path().filename() == "notes.txt" || e.path().filename() == ".peensim.lock") << e.path();
    EXPECT_TRUE(fs::exists(dir.path / "mine" / "notes.txt"));
}

}  // namespace
}  // namespace peensim::testing
