// A run's replicas over MPI ranks (app/run/replica_ranks.h): `mpirun -n K peensim run --replicas K`
// gives the bytes of the same replicas on threads, refuses a rank count other than K and a run
// until coverage (its rounds run on threads only) with exit 2, and an interrupted rank 0 stops the
// others and resumes as one replica; the result and the plan travel between ranks as bytes that
// come back the same.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "app/exit_codes.h"
#include "app/run/replica_result_codec.h"
#include "output/impact_csv_writer.h"
#include "support/files.h"
#include "support/mpirun_environment.h"
#include "support/run_in_process.h"
#include "support/shell_command.h"
#include "support/temp_dir.h"

namespace peensim::testing {
namespace replica_ranks_cases {

namespace fs = std::filesystem;

const std::string kMpirun = "/usr/bin/mpirun";

// `mpirun -n ranks peensim run rod.yaml --replicas replicas` of 4 s into dir, with `extra` options.
ShellResult run_over_ranks(const fs::path& dir, int ranks, int replicas, const std::string& extra = "") {
    mpirun_environment();
    return run_shell(kMpirun + " -n " + std::to_string(ranks) + " --oversubscribe " + PEENSIM_BINARY + " run " + PEENSIM_SOURCE_DIR +
                     "/scenes/rod.yaml -o " + dir.string() + " --quiet --no-analyze --no-render --replicas " + std::to_string(replicas) +
                     " --set process.duration=4 --set process.seed=1 " + extra);
}

// The same run in this process, its replicas (if any) on threads.
InProcessResult run_on_threads(const fs::path& dir, int replicas) {
    InProcessRun r;
    r.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml";
    r.output_dir = dir.string();
    r.replicas = replicas;
    r.overrides = {"process.duration=4", "process.seed=1"};
    return run_in_process(r);
}

int exit_code(const ShellResult& r) { return WIFEXITED(r.status) ? WEXITSTATUS(r.status) : -1; }

nlohmann::json summary_of(const fs::path& dir) { return nlohmann::json::parse(read_file(dir / "summary.json")); }

TEST(ReplicaRanks, OverMpiRanksARunHasTheBytesOfItsReplicasOnThreads) {
    ASSERT_TRUE(fs::exists(kMpirun)) << "mpirun not found: .ci/install-deps installs openmpi-bin";
    TempDir dir;
    const ShellResult ranks = run_over_ranks(dir.path / "ranks", 2, 2);
    ASSERT_EQ(exit_code(ranks), kExitOk) << ranks.output;
    const InProcessResult t = run_on_threads(dir.path / "threads", 2);
    ASSERT_EQ(t.code, kExitOk) << t.err;
    EXPECT_EQ(read_file(dir.path / "ranks" / kImpactCsvFileName), read_file(dir.path / "threads" / kImpactCsvFileName));
    const nlohmann::json a = summary_of(dir.path / "ranks"), b = summary_of(dir.path / "threads");
    ASSERT_TRUE(a.contains("replicas")) << ranks.output;
    EXPECT_EQ(a["replicas"], b["replicas"]);
    for (const char* key : {"impacts_per_component", "slow_contacts_per_component", "health_counters", "normal_speed", "steps",
                            "shot_steps", "simulated_time_s", "shots_in_flight", "shots_at_rest"})
        EXPECT_EQ(a[key], b[key]) << key;
    EXPECT_FALSE(fs::exists(dir.path / "ranks" / "replicas"));  // the spills are gone
}

TEST(ReplicaRanks, ARankCountOtherThanTheReplicasExitsTwoSayingBoth) {
    ASSERT_TRUE(fs::exists(kMpirun)) << "mpirun not found: .ci/install-deps installs openmpi-bin";
    TempDir dir;
    const ShellResult r = run_over_ranks(dir.path / "out", 2, 3);
    EXPECT_EQ(exit_code(r), kExitInputError) << r.output;
    EXPECT_NE(r.output.find("--replicas 3 in an MPI job of 2 ranks: expected --replicas 2"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.path / "out" / kImpactCsvFileName));
}

// A run until coverage runs its replicas in rounds on threads only: over ranks it exits 2 before
// anything is written, saying what to do instead, and no rank is left waiting.
TEST(ReplicaRanks, ARunUntilCoverageIsRefusedOverRanksSayingToUseThreads) {
    ASSERT_TRUE(fs::exists(kMpirun)) << "mpirun not found: .ci/install-deps installs openmpi-bin";
    TempDir dir;
    const ShellResult r = run_over_ranks(dir.path / "out", 2, 2, "--until-coverage 20%");
    EXPECT_EQ(exit_code(r), kExitInputError) << r.output;
    EXPECT_NE(r.output.find("--replicas"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("without mpirun"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.path / "out" / kImpactCsvFileName));
}

TEST(ReplicaRanks, AnInterruptedRankZeroStopsTheOthersAndResumesAsOne) {
    ASSERT_TRUE(fs::exists(kMpirun)) << "mpirun not found: .ci/install-deps installs openmpi-bin";
    TempDir dir;
    const ShellResult stopped = run_over_ranks(dir.path / "run", 2, 2, "--stop-after-steps 2500");
    EXPECT_EQ(exit_code(stopped), kExitInterrupted) << stopped.output;
    EXPECT_NE(stopped.output.find("the other replicas' work is dropped"), std::string::npos) << stopped.output;
    EXPECT_FALSE(fs::exists(dir.path / "run" / "replicas"));
    const ShellResult resumed = run_over_ranks(dir.path / "run", 2, 2, "--resume");
    ASSERT_EQ(exit_code(resumed), kExitOk) << resumed.output;
    ASSERT_EQ(run_on_threads(dir.path / "plain", 1).code, kExitOk);
    EXPECT_EQ(read_file(dir.path / "run" / kImpactCsvFileName), read_file(dir.path / "plain" / kImpactCsvFileName));
}

// Ranks that do not share the run's directory (here: each started in its own working directory,
// the run's -o relative) are told apart before any replica runs, with a message that says why.
TEST(ReplicaRanks, ARankThatCannotSeeTheRunsDirectorySaysSoBeforeItRuns) {
    ASSERT_TRUE(fs::exists(kMpirun)) << "mpirun not found: .ci/install-deps installs openmpi-bin";
    TempDir dir;
    fs::create_directories(dir.path / "a");
    fs::create_directories(dir.path / "b");
    mpirun_environment();
    const std::string args = std::string(" ") + PEENSIM_BINARY + " run " + PEENSIM_SOURCE_DIR +
                             "/scenes/rod.yaml -o out --quiet --no-analyze --no-render --replicas 2 --set process.duration=4";
    const ShellResult r = run_shell(kMpirun + " --oversubscribe -n 1 --wdir " + (dir.path / "a").string() + args + " : -n 1 --wdir " +
                                    (dir.path / "b").string() + args);
    EXPECT_NE(exit_code(r), kExitOk) << r.output;
    EXPECT_NE(r.output.find("replica 1 (MPI rank 1): cannot see the run's directory out as rank 0 made it"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.path / "b" / "out"));  // rank 1 wrote nothing of its own
}

TEST(ReplicaResultCodec, AResultAndAPlanComeBackTheSameAndOtherBytesAreRefused) {
    ReplicaResult r;
    r.window = {3, 0x9E3779B97F4A7C15ull, 0.125, 17.5, 42.25};
    r.summary.impacts_per_component = {{"shot-shot", 7}, {"rod", 123456789}};
    r.summary.slow_contacts_per_component = {{"shot-shot", 1}, {"rod", 2}};
    r.summary.health_counters = {{"shot_lost", 0}, {"grazes", 5}};
    r.summary.stage_times = {{"integrate", 1.5}, {"mesh_queries", 0.25}};
    r.summary.steps = 11;
    r.summary.shot_steps = 12;
    r.summary.shot_lost = 1;
    r.summary.shots_in_flight = 13;
    r.summary.shots_at_rest = 14;
    r.summary.finished = true;
    r.impacts_at_window_start = {1, 2, 3};
    r.slow_contacts_at_window_start = {4, 5};
    r.speeds.resize(2);
    r.speeds[0].add(1.25);
    r.speeds[1].add(0.5);
    r.logged_impacts = 99;
    LostShot lost;
    lost.shot = 8;
    lost.time_s = 2.5;
    lost.position_m = Vec3(1, 2, 3);
    lost.cause = LossCause::not_diagnosed;
    lost.component = 2;
    lost.radius_m = 1e-3;
    r.lost = {lost};
    r.health.non_finite = 5;
    r.wall_s = 3.75;
    const ReplicaResult back = decode_replica_result(encode_replica_result(r));
    EXPECT_EQ(encode_replica_result(back), encode_replica_result(r));
    EXPECT_EQ(back.window.seed, r.window.seed);
    EXPECT_EQ(back.window.shift_s, 42.25);
    EXPECT_EQ(back.summary.impacts_per_component[1].name, "rod");
    EXPECT_EQ(back.summary.impacts_per_component[1].count, 123456789u);
    EXPECT_EQ(back.speeds[0].serialize(), r.speeds[0].serialize());
    ASSERT_EQ(back.lost.size(), 1u);
    EXPECT_EQ(back.lost[0].position_m, Vec3(1, 2, 3));
    EXPECT_EQ(back.health.non_finite, 5u);
    EXPECT_EQ(back.wall_s, 3.75);

    ReplicaPlan plan;
    plan.pilot_s = 1.875;
    plan.warm_up_s = 0.15;
    plan.turn_s = 2.0;
    plan.windows = {{}, r.window};
    const ReplicaPlan p = decode_replica_plan(encode_replica_plan(plan));
    EXPECT_EQ(encode_replica_plan(p), encode_replica_plan(plan));
    EXPECT_TRUE(decode_replica_plan(encode_replica_plan(ReplicaPlan{})).windows.empty());

    const std::string bytes = encode_replica_result(r);
    EXPECT_THROW(decode_replica_result(bytes.substr(0, bytes.size() - 1)), std::runtime_error);
    EXPECT_THROW(decode_replica_result(bytes + "x"), std::runtime_error);
    EXPECT_THROW(decode_replica_result(encode_replica_plan(plan)), std::runtime_error);
    EXPECT_THROW(decode_replica_plan(bytes), std::runtime_error);
}

}  // namespace replica_ranks_cases
}  // namespace peensim::testing
