// Ctrl-C and SIGTERM. The guard: a first signal only raises the flag, a second ends the process at
// once with exit 130 and one line on stderr, and the previous handlers come back. The `peensim`
// binary on the rod scene: one SIGINT stops the run within 1 s of wall time (each stepping scheme;
// SIGTERM too on the gear turning at 3000 rpm and the soft scheme's gear)
// with exit 130 and a checkpoint; a second SIGINT abandons the stop at once, exit 130, leaving the
// last periodic checkpoint whole, and a run resumed from it ends with the uninterrupted impacts.csv.
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "app/checkpoint/checkpoint.h"
#include "app/interrupt.h"
#include "app/run/run_job.h"
#include "output/impact_csv_writer.h"
#include "support/child_process.h"
#include "support/files.h"
#include "support/temp_dir.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

constexpr double kStopLimitS = 1.0;    // s of wall time from a signal to the end of the process
constexpr double kStartLimitS = 60.0;  // s, generous: the machine may be busy with builds
constexpr double kRunLimitS = 300.0;   // s, for runs that must finish

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Waits (at most kStartLimitS) until `path` exists; false if the child ended first or time ran out.
bool wait_for_file(ChildProcess& child, const fs::path& path) {
    const auto t0 = std::chrono::steady_clock::now();
    while (!fs::exists(path)) {
        if (!child.running() || seconds_since(t0) > kStartLimitS) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return true;
}

// `peensim run` on the shipped rod scene with a checkpoint every 0.2 s of wall time.
std::vector<std::string> rod_run(const fs::path& dir, const std::string& scheme, const std::string& duration_s) {
    return {PEENSIM_BINARY,
            "run",
            std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml",
            "-o",
            dir.string(),
            "--quiet",
            "--no-analyze",
            "--scheme",
            scheme,
            "--set",
            "process.duration=" + duration_s,
            "--set",
            "output.checkpoint_interval=0.2"};
}

TEST(InterruptGuard, FirstSignalOnlyRaisesTheFlag) {
    InterruptGuard guard("abandoned\n");
    EXPECT_FALSE(InterruptGuard::requested());
    std::raise(SIGINT);
    EXPECT_TRUE(InterruptGuard::requested());
}

TEST(InterruptGuard, PreviousHandlersComeBack) {
    struct sigaction before_int {
    }, before_term{}, after_int{}, after_term{};
    sigaction(SIGINT, nullptr, &before_int);
    sigaction(SIGTERM, nullptr, &before_term);
    { InterruptGuard guard("abandoned\n"); }
    sigaction(SIGINT, nullptr, &after_int);
    sigaction(SIGTERM, nullptr, &after_term);
    EXPECT_EQ(after_int.sa_handler, before_int.sa_handler);
    EXPECT_EQ(after_term.sa_handler, before_term.sa_handler);
}

TEST(InterruptGuardDeathTest, SecondSignalEndsTheProcessAtOnceWith130) {
    // Ctrl-C then SIGTERM (either order, either signal twice: one count).
    EXPECT_EXIT(
        {
            InterruptGuard guard("run abandoned here\n");
            std::raise(SIGINT);
            std::raise(SIGTERM);
            std::abort();  // not reached
        },
        ::testing::ExitedWithCode(kExitInterrupted), "run abandoned here");
    EXPECT_EXIT(
        {
            InterruptGuard guard("run abandoned again\n");
            std::raise(SIGINT);
            std::raise(SIGINT);
            std::abort();
        },
        ::testing::ExitedWithCode(kExitInterrupted), "run abandoned again");
}

class RunInterrupt : public ::testing::TestWithParam<std::string> {};

TEST_P(RunInterrupt, OneSignalStopsWithinASecondWithACheckpoint) {
    // A 100 s run (hours of wall time) interrupted once its first checkpoint is there. Time
    // stepping stops at the end of the current step; the event-driven scheme at its next restart
    // point (every 0.1 s of simulated time on this branch).
    TempDir dir;
    ChildProcess run(rod_run(dir.path / "out", GetParam(), "100"), (dir.path / "stdout").string(), (dir.path / "stderr").string());
    ASSERT_TRUE(wait_for_file(run, dir.path / "out" / kCheckpointFileName)) << read_file(dir.path / "stderr");
    const auto t0 = std::chrono::steady_clock::now();
    run.signal(SIGINT);
    const std::optional<int> code = run.wait_exit(kRunLimitS);
    const double stop_s = seconds_since(t0);
    std::cout << "[ stop     ] " << GetParam() << " scheme: exit " << code.value_or(-1) << " " << stop_s << " s after SIGINT\n";
    const std::string err = read_file(dir.path / "stderr");
    ASSERT_EQ(code, kExitInterrupted) << err;
    EXPECT_LT(stop_s, kStopLimitS) << err;
    EXPECT_NE(err.find("interrupted at t ="), std::string::npos) << err;
    EXPECT_EQ(err.find("abandoned"), std::string::npos) << err;
    const Checkpoint c = load_checkpoint((dir.path / "out" / kCheckpointFileName).string());
    EXPECT_GT(c.state.time.seconds(), 0.0);
    EXPECT_TRUE(fs::exists(dir.path / "out" / "summary.json"));
}

INSTANTIATE_TEST_SUITE_P(Schemes, RunInterrupt, ::testing::Values(std::string("step"), std::string("event")),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// SIGTERM (what a batch system sends) on the scenes that work the engine hardest: the gear turning
// at 3000 rpm (moving-mesh searches, grazes, sustained contact) in each rigid scheme, and the soft
// scheme's gear. Each stops within 1 s of wall time with a checkpoint.
struct HardRun {
    std::string name, scene, scheme;
    std::vector<std::string> sets;
};

// gtest's own printer would dump the case's bytes, unset ones among them (valgrind reports them
// as uninitialised at every start of the test binary).
void PrintTo(const HardRun& p, std::ostream* os) { *os << p.name << " " << p.scheme; }
class RunInterruptHard : public ::testing::TestWithParam<HardRun> {};

TEST_P(RunInterruptHard, SigtermStopsWithinASecondWithACheckpoint) {
    const HardRun& p = GetParam();
    TempDir dir;
    std::vector<std::string> args = {PEENSIM_BINARY,
                                     "run",
                                     std::string(PEENSIM_SOURCE_DIR) + "/scenes/" + p.scene,
                                     "-o",
                                     (dir.path / "out").string(),
                                     "--quiet",
                                     "--no-analyze",
                                     "--scheme",
                                     p.scheme,
                                     "--set",
                                     "process.duration=100",
                                     "--set",
                                     "output.checkpoint_interval=0.2"};
    for (const std::string& set : p.sets) args.insert(args.end(), {"--set", set});
    ChildProcess run(args, (dir.path / "stdout").string(), (dir.path / "stderr").string());
    ASSERT_TRUE(wait_for_file(run, dir.path / "out" / kCheckpointFileName)) << read_file(dir.path / "stderr");
    std::this_thread::sleep_for(std::chrono::milliseconds(500));  // well into the run
    const auto t0 = std::chrono::steady_clock::now();
    run.signal(SIGTERM);
    const std::optional<int> code = run.wait_exit(kRunLimitS);
    const double stop_s = seconds_since(t0);
    std::cout << "[ stop     ] " << p.name << ": exit " << code.value_or(-1) << " " << stop_s << " s after SIGTERM\n";
    const std::string err = read_file(dir.path / "stderr");
    ASSERT_EQ(code, kExitInterrupted) << err;
    EXPECT_LT(stop_s, kStopLimitS) << err;
    EXPECT_NE(err.find("interrupted at t ="), std::string::npos) << err;
    const Checkpoint c = load_checkpoint((dir.path / "out" / kCheckpointFileName).string());
    EXPECT_GT(c.state.time.seconds(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, RunInterruptHard,
    ::testing::Values(HardRun{"gear_3000rpm_event", "rotating-gear.yaml", "event", {"components[gear].motion.speed=3000 rpm"}},
                      HardRun{"gear_3000rpm_step", "rotating-gear.yaml", "step", {"components[gear].motion.speed=3000 rpm"}},
                      HardRun{"gear_soft", "gear-soft.yaml", "soft", {}}),
    [](const ::testing::TestParamInfo<HardRun>& info) { return info.param.name; });

TEST(RunInterruptTwice, SecondSignalAbandonsAtOnceAndTheLastCheckpointResumes) {
    // The event-driven scheme (its stop waits for a restart point, so the second SIGINT finds the
    // run still stopping), 3 s of simulated time (a few s of wall time).
    TempDir dir;
    const fs::path whole = dir.path / "whole", parts = dir.path / "parts";
    {
        ChildProcess run(rod_run(whole, "event", "3"), (dir.path / "whole.out").string(), (dir.path / "whole.err").string());
        ASSERT_EQ(run.wait_exit(kRunLimitS), kExitOk) << read_file(dir.path / "whole.err");
    }
    {
        ChildProcess run(rod_run(parts, "event", "3"), (dir.path / "parts.out").string(), (dir.path / "parts.err").string());
        ASSERT_TRUE(wait_for_file(run, parts / kCheckpointFileName)) << read_file(dir.path / "parts.err");
        run.signal(SIGINT);
        // Two SIGINTs pending at once would count as one: the second goes once the first is taken.
        ASSERT_TRUE(run.wait_signal_delivered(SIGINT, kStartLimitS));
        const auto t0 = std::chrono::steady_clock::now();
        run.signal(SIGINT);
        const std::optional<int> code = run.wait_exit(kRunLimitS);
        const double stop_s = seconds_since(t0);
        std::cout << "[ abandon  ] exit " << code.value_or(-1) << " " << stop_s << " s after the second SIGINT\n";
        const std::string err = read_file(dir.path / "parts.err");
        ASSERT_EQ(code, kExitInterrupted) << err;
        EXPECT_LT(stop_s, kStopLimitS) << err;
        EXPECT_NE(err.find("run abandoned"), std::string::npos) << err;
        EXPECT_NE(err.find("--resume"), std::string::npos) << err;
    }
    const Checkpoint c = load_checkpoint((parts / kCheckpointFileName).string());  // whole, not cut
    std::cout << "[ abandon  ] the checkpoint left holds t = " << c.state.time.seconds() << " s\n";
    EXPECT_GE(c.state.time.seconds(), 0.0);  // a run checkpoints its start: this may be that one
    EXPECT_LT(c.state.time.seconds(), 3.0);
    {
        std::vector<std::string> args = rod_run(parts, "event", "3");
        args.push_back("--resume");
        ChildProcess run(args, (dir.path / "resume.out").string(), (dir.path / "resume.err").string());
        ASSERT_EQ(run.wait_exit(kRunLimitS), kExitOk) << read_file(dir.path / "resume.err");
    }
    const std::string expected = read_file(whole / kImpactCsvFileName);
    ASSERT_FALSE(expected.empty());
    EXPECT_TRUE(expected == read_file(parts / kImpactCsvFileName)) << "the resumed run differs from the uninterrupted one";
}

}  // namespace
}  // namespace peensim::testing
