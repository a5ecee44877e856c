// A run's replicas over MPI ranks (app/run/replica_ranks.h): `mpirun -n K peensim run --replicas K`
// gives the bytes of the same replicas on threads, and so does a run until coverage (its rounds);
// a rank count other than K exits 2, an interrupted rank 0 stops the others and resumes as one
// replica; the results, slots and plans travel between ranks as bytes that come back the same.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "app/exit_codes.h"
#include "app/run/replica_result_codec.h"
#include "output/impact_csv_writer.h"
#include "support/files.h"
#include "support/mpirun_environment.h"
#include "support/replica_slots.h"
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

// A run until coverage over ranks: the rod to `target`, its replicas in rounds, capped at 60 s.
std::string until(const std::string& target) {
    return "--until-coverage " + target + " --set process.duration=60 --set output.checkpoint_interval=0.5";
}

// The same run until coverage in this process, its replicas on threads.
InProcessResult run_until_on_threads(const fs::path& dir, int replicas, const std::string& target,
                                     std::optional<std::uint64_t> stop_after_steps = {}, bool resume = false) {
    InProcessRun r;
    r.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml";
    r.output_dir = dir.string();
    r.replicas = replicas;
    r.overrides = {"process.duration=60", "process.seed=1", "process.until_coverage=" + target, "output.checkpoint_interval=0.5"};
    r.stop_after_steps = stop_after_steps;
    r.resume = resume;
    return run_in_process(r);
}

// Rounds over ranks: the log of the same rounds on threads, byte for byte, with the same slots,
// the same end and the same counts in the summary; 3 ranks, so that a round waits for two, to 70 %
// (two rounds and more).
TEST(ReplicaRanks, OverMpiRanksARunUntilCoverageHasTheBytesOfItsRoundsOnThreads) {
    ASSERT_TRUE(fs::exists(kMpirun)) << "mpirun not found: .ci/install-deps installs openmpi-bin";
    TempDir dir;
    const ShellResult ranks = run_over_ranks(dir.path / "ranks", 3, 3, until("70%"));
    ASSERT_EQ(exit_code(ranks), kExitOk) << ranks.output;
    const InProcessResult t = run_until_on_threads(dir.path / "threads", 3, "70%");
    ASSERT_EQ(t.code, kExitOk) << t.err;
    EXPECT_EQ(read_file(dir.path / "ranks" / kImpactCsvFileName), read_file(dir.path / "threads" / kImpactCsvFileName));
    const nlohmann::json a = summary_of(dir.path / "ranks"), b = summary_of(dir.path / "threads");
    ASSERT_TRUE(a.contains("replicas")) << ranks.output;
    EXPECT_GE(a["replicas"]["windows"].size(), 6u) << "two rounds at least";
    EXPECT_TRUE(a["until_coverage"]["reached"].get<bool>());
    for (const char* key :
         {"replicas", "until_coverage", "impacts_per_component", "slow_contacts_per_component", "normal_speed", "simulated_time_s"})
        EXPECT_EQ(a[key], b[key]) << key;
    EXPECT_FALSE(fs::exists(dir.path / "ranks" / "replicas"));  // the spills are gone
}

// Rank 0 stopped in its second slot (after rank 1's first slot is logged) stops rank 1 and keeps
// the log it had, as on threads; resumed over ranks, it goes on as one replica to the bytes of
// the same run resumed on threads.
TEST(ReplicaRanks, AnInterruptedRankZeroInRoundsStopsTheOthersAndResumesAsOne) {
    ASSERT_TRUE(fs::exists(kMpirun)) << "mpirun not found: .ci/install-deps installs openmpi-bin";
    TempDir dir;
    const InProcessResult whole = run_until_on_threads(dir.path / "whole", 2, "50%");
    ASSERT_EQ(whole.code, kExitOk) << whole.err;
    const nlohmann::json ws = summary_of(dir.path / "whole");
    const double second_round_s = ws["replicas"]["windows"][1]["end_s"].get<double>();
    const std::uint64_t stop_steps = steps_into_second_slot(ws);
    const ShellResult stopped =
        run_over_ranks(dir.path / "ranks", 2, 2, until("50%") + " --stop-after-steps " + std::to_string(stop_steps));
    EXPECT_EQ(exit_code(stopped), kExitInterrupted) << stopped.output;
    EXPECT_NE(stopped.output.find("other replicas' work since their last logged round is dropped"), std::string::npos) << stopped.output;
    EXPECT_FALSE(fs::exists(dir.path / "ranks" / "replicas"));
    ASSERT_GT(summary_of(dir.path / "ranks")["simulated_time_s"].get<double>(), second_round_s)
        << "the stop must come in replica 0's second slot for this test";
    ASSERT_EQ(run_until_on_threads(dir.path / "threads", 2, "50%", stop_steps).code, kExitInterrupted);
    EXPECT_EQ(read_file(dir.path / "ranks" / kImpactCsvPartialFileName), read_file(dir.path / "threads" / kImpactCsvPartialFileName));
    const ShellResult resumed = run_over_ranks(dir.path / "ranks", 2, 2, until("50%") + " --resume");
    ASSERT_EQ(exit_code(resumed), kExitOk) << resumed.output;
    ASSERT_EQ(run_until_on_threads(dir.path / "threads", 2, "50%", std::nullopt, true).code, kExitOk);
    EXPECT_EQ(read_file(dir.path / "ranks" / kImpactCsvFileName), read_file(dir.path / "threads" / kImpactCsvFileName));
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
    for (const std::string& kind : {std::string(), until("50%")}) {  // windows, rounds
        const std::string args = std::string(" ") + PEENSIM_BINARY + " run " + PEENSIM_SOURCE_DIR +
                                 "/scenes/rod.yaml -o out --quiet --no-analyze --no-render --replicas 2 --set process.duration=4 " + kind;
        const ShellResult r = run_shell(kMpirun + " --oversubscribe -n 1 --wdir " + (dir.path / "a").string() + args + " : -n 1 --wdir " +
                                        (dir.path / "b").string() + args);
        EXPECT_NE(exit_code(r), kExitOk) << kind << r.output;
        EXPECT_NE(r.output.find("replica 1 (MPI rank 1): cannot see the run's directory out as rank 0 made it"), std::string::npos)
            << kind << r.output;
        EXPECT_FALSE(fs::exists(dir.path / "b" / "out"));  // rank 1 wrote nothing of its own
    }
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

TEST(ReplicaResultCodec, ARoundsPlanASlotAndARoundResultComeBackTheSameAndOtherBytesAreRefused) {
    RoundPlan plan;
    plan.pilot_s = 1.0;
    plan.warm_up_s = 0.15;
    plan.turn_s = 2.0;
    plan.first_s = 7.25;
    plan.round_s = 5.125;
    plan.seeds = {1, 0x9E3779B97F4A7C15ull, 3};
    plan.first_from_s = {0.0, 8.0, 8.5};
    const RoundPlan p = decode_round_plan(encode_round_plan(plan));
    EXPECT_EQ(encode_round_plan(p), encode_round_plan(plan));
    EXPECT_EQ(p.seeds, plan.seeds);
    EXPECT_EQ(p.first_from_s, plan.first_from_s);
    EXPECT_EQ(p.slot(3, 2).shift_s, plan.slot(3, 2).shift_s);
    EXPECT_TRUE(is_round_plan(encode_round_plan(plan)));
    EXPECT_FALSE(is_round_plan(encode_replica_plan(ReplicaPlan{})));  // "none" is a replicas' plan
    EXPECT_FALSE(is_round_plan("RN"));

    SlotResult slot;
    slot.window = {2, 77, 8.0, 13.125, 40.5};
    slot.spill = "out/replicas/replica-2.round-4.impacts.bin";
    slot.logged_impacts = 8123;
    slot.impacts_at_start = {1, 2, 3};
    slot.slow_contacts_at_start = {4, 5, 6};
    slot.impacts_at_end = {7, 8, 9};
    slot.slow_contacts_at_end = {10, 11, 12};
    const SlotResult s = decode_slot_result(encode_slot_result(slot));
    EXPECT_EQ(encode_slot_result(s), encode_slot_result(slot));
    EXPECT_EQ(s.spill, slot.spill);
    EXPECT_EQ(s.impacts_at_end, slot.impacts_at_end);

    RoundReplicaResult r;
    r.replica = 2;
    r.seed = 77;
    r.first_from_s = 8.0;
    r.summary.impacts_per_component = {{"shot-shot", 7}, {"rod", 123456789}};
    r.summary.stage_times = {{"mesh_queries", 0.25}};
    r.summary.steps = 11;
    r.summary.shot_lost = 1;
    LostShot lost;
    lost.shot = 8;
    lost.position_m = Vec3(1, 2, 3);
    r.lost = {lost};
    r.health.non_finite = 5;
    const RoundReplicaResult back = decode_round_replica_result(encode_round_replica_result(r));
    EXPECT_EQ(encode_round_replica_result(back), encode_round_replica_result(r));
    EXPECT_EQ(back.summary.impacts_per_component[1].count, 123456789u);
    EXPECT_EQ(back.lost[0].position_m, Vec3(1, 2, 3));
    EXPECT_EQ(back.health.non_finite, 5u);

    const std::string bytes = encode_slot_result(slot);
    EXPECT_THROW(decode_slot_result(bytes.substr(0, bytes.size() - 1)), std::runtime_error);
    EXPECT_THROW(decode_slot_result(bytes + "x"), std::runtime_error);
    EXPECT_THROW(decode_round_replica_result(bytes), std::runtime_error);
    EXPECT_THROW(decode_round_plan(bytes), std::runtime_error);
    EXPECT_THROW(decode_slot_result(encode_round_plan(plan)), std::runtime_error);
}

}  // namespace replica_ranks_cases
}  // namespace peensim::testing
