// `peensim run --replicas K` (app/run/replica_plan.h): one impacts.csv of the replicas' windows in
// time order whose counts add up, the same bytes for the same seed and K, the statistics of one
// trajectory within noise, a run too short for it going on as one replica (the bytes of a plain
// run), an interrupted one resuming as one, and scenes that are not steady refused with exit 2.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "app/exit_codes.h"
#include "output/impact_csv_writer.h"
#include "support/files.h"
#include "support/run_in_process.h"
#include "support/shell_command.h"
#include "support/temp_dir.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

const std::string kRod = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml";

nlohmann::json summary_of(const fs::path& dir) { return nlohmann::json::parse(read_file(dir / "summary.json")); }

std::uint64_t impacts_on(const nlohmann::json& summary, const std::string& component) {
    for (const auto& c : summary["impacts_per_component"])
        if (c["component"] == component) return c["impacts"].get<std::uint64_t>();
    return 0;
}

std::vector<double> impact_times(const fs::path& dir) {
    std::ifstream in(dir / kImpactCsvFileName);
    std::string line;
    std::getline(in, line);  // header
    std::vector<double> t;
    while (std::getline(in, line)) t.push_back(std::stod(line.substr(0, line.find(','))));
    return t;
}

InProcessResult run_rod(const fs::path& dir, double duration_s, int replicas, std::uint64_t seed = 1, bool analyze = false) {
    InProcessRun r;
    r.analyze = analyze;
    r.scene_path = kRod;
    r.output_dir = dir.string();
    r.replicas = replicas;
    r.overrides = {"process.duration=" + std::to_string(duration_s), "process.seed=" + std::to_string(seed)};
    return run_in_process(r);
}

TEST(Replicas, OneLogOfTheWindowsInTimeOrderWhoseCountsAddUpAndTheSameBytesTwice) {
    TempDir dir;
    const InProcessResult a = run_rod(dir.path / "a", 4.0, 2);
    ASSERT_EQ(a.code, kExitOk) << a.err;
    const nlohmann::json s = summary_of(dir.path / "a");
    ASSERT_TRUE(s.contains("replicas")) << a.err;
    const auto& windows = s["replicas"]["windows"];
    ASSERT_EQ(windows.size(), 2u);
    EXPECT_EQ(windows[0]["start_s"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(windows[1]["start_s"].get<double>(), windows[0]["end_s"].get<double>());
    EXPECT_NEAR(windows[1]["end_s"].get<double>(), 4.0, 1e-12);
    EXPECT_GT(windows[1]["own_start_s"].get<double>(), 0.0);  // the measured warm-up, not logged
    EXPECT_EQ(s["simulated_time_s"].get<double>(), 4.0);
    EXPECT_TRUE(s["finished"].get<bool>());

    const std::vector<double> t = impact_times(dir.path / "a");
    const std::uint64_t logged = windows[0]["logged_impacts"].get<std::uint64_t>() + windows[1]["logged_impacts"].get<std::uint64_t>();
    EXPECT_EQ(t.size(), logged);
    EXPECT_EQ(impacts_on(s, "rod"), logged);
    EXPECT_TRUE(std::is_sorted(t.begin(), t.end()));
    EXPECT_GE(t.front(), 0.0);
    EXPECT_LT(t.back(), 4.0);
    // Each window's impacts inside it.
    const double boundary = windows[1]["start_s"].get<double>();
    const auto first_of_second = std::lower_bound(t.begin(), t.end(), boundary);
    EXPECT_EQ(static_cast<std::uint64_t>(first_of_second - t.begin()), windows[0]["logged_impacts"].get<std::uint64_t>());
    EXPECT_FALSE(fs::exists(dir.path / "a" / "replicas"));  // the spills are gone

    const InProcessResult b = run_rod(dir.path / "b", 4.0, 2);
    ASSERT_EQ(b.code, kExitOk) << b.err;
    EXPECT_EQ(read_file(dir.path / "a" / kImpactCsvFileName), read_file(dir.path / "b" / kImpactCsvFileName));
}

// Every window follows a start from rest: the report says so beside the forecasts, with the
// shortest window (shorter windows scatter more), and a run as one trajectory's does not.
TEST(Replicas, TheReportSaysEachWindowFollowsAStartFromRest) {
    TempDir dir;
    const InProcessResult k2 = run_rod(dir.path / "k2", 4.0, 2, 1, true);
    ASSERT_EQ(k2.code, kExitOk) << k2.err;
    const nlohmann::json summary = summary_of(dir.path / "k2");
    const auto& windows = summary["replicas"]["windows"];
    ASSERT_EQ(windows.size(), 2u);
    const double shortest = std::min(windows[0]["end_s"].get<double>() - windows[0]["start_s"].get<double>(),
                                     windows[1]["end_s"].get<double>() - windows[1]["start_s"].get<double>());
    std::ostringstream expected;
    expected << "**A run as 2 replicas:** each of its windows (the shortest " << std::setprecision(3) << shortest
             << " s) follows a start from rest, logged from its measured warm-up on.";
    const std::string report = read_file(dir.path / "k2" / "analysis" / "report.md");
    EXPECT_NE(report.find(expected.str()), std::string::npos) << expected.str() << "\n" << report;

    // The same report without the replicas' summary (as a run of one trajectory has): no such line.
    nlohmann::json plain = summary_of(dir.path / "k2");
    plain.erase("replicas");
    std::ofstream(dir.path / "k2" / "summary.json") << plain.dump();
    const ShellResult analyzed = run_shell(std::string(PEENSIM_BINARY) + " analyze " + (dir.path / "k2").string());
    ASSERT_EQ(analyzed.status, 0) << analyzed.output;
    EXPECT_EQ(read_file(dir.path / "k2" / "analysis" / "report.md").find("replicas:**"), std::string::npos);
}

TEST(Replicas, ARunTooShortForThePilotGoesOnAsOneReplicaWithThePlainRunsBytes) {
    TempDir dir;
    const InProcessResult one = run_rod(dir.path / "one", 1.0, 1);
    const InProcessResult two = run_rod(dir.path / "two", 1.0, 2);
    ASSERT_EQ(one.code, kExitOk) << one.err;
    ASSERT_EQ(two.code, kExitOk) << two.err;
    EXPECT_NE(two.err.find("goes on as one replica"), std::string::npos) << two.err;
    EXPECT_FALSE(summary_of(dir.path / "two").contains("replicas"));
    EXPECT_EQ(read_file(dir.path / "one" / kImpactCsvFileName), read_file(dir.path / "two" / kImpactCsvFileName));
}

TEST(Replicas, TheImpactStatisticsAreOneTrajectorysWithinNoise) {
    // Four seeds of 4 s, as one trajectory and as two replicas: the rod's impact rate and mean
    // normal speed agree within three standard errors of their difference (the spread between
    // seeds: impacts come in bursts, so Poisson's error would be too small).
    TempDir dir;
    std::vector<double> rate[2], speed[2];
    for (int replicas = 1; replicas <= 2; ++replicas) {
        for (std::uint64_t seed = 1; seed <= 4; ++seed) {
            const fs::path d = dir.path / ("r" + std::to_string(replicas) + "s" + std::to_string(seed));
            const InProcessResult r = run_rod(d, 4.0, replicas, seed);
            ASSERT_EQ(r.code, kExitOk) << r.err;
            const nlohmann::json s = summary_of(d);
            ASSERT_EQ(s.contains("replicas"), replicas == 2) << r.err;
            rate[replicas - 1].push_back(static_cast<double>(impacts_on(s, "rod")) / 4.0);
            speed[replicas - 1].push_back(s["normal_speed"][0]["mean_normal_speed_mps"].get<double>());
        }
    }
    const auto mean = [](const std::vector<double>& v) {
        double m = 0.0;
        for (const double x : v) m += x;
        return m / static_cast<double>(v.size());
    };
    const auto variance_of_mean = [&](const std::vector<double>& v) {
        const double m = mean(v);
        double s = 0.0;
        for (const double x : v) s += (x - m) * (x - m);
        return s / static_cast<double>(v.size() - 1) / static_cast<double>(v.size());
    };
    for (const auto* q : {rate, speed}) {
        const double diff = mean(q[1]) - mean(q[0]);
        const double se = std::sqrt(variance_of_mean(q[0]) + variance_of_mean(q[1]));
        EXPECT_LT(std::abs(diff), 3.0 * se + 1e-3 * std::abs(mean(q[0]))) << "one: " << mean(q[0]) << ", replicas: " << mean(q[1]);
    }
}

TEST(Replicas, AnInterruptedRunDropsTheOtherReplicasAndResumesAsOne) {
    TempDir dir;
    InProcessRun r;
    r.scene_path = kRod;
    r.output_dir = (dir.path / "run").string();
    r.replicas = 2;
    r.overrides = {"process.duration=4"};
    r.stop_after_steps = 1800;  // past the pilot (1 s), before replica 0's end (2.5 s)
    const InProcessResult stopped = run_in_process(r);
    ASSERT_EQ(stopped.code, kExitInterrupted) << stopped.err;
    EXPECT_NE(stopped.err.find("other replicas' work is dropped"), std::string::npos) << stopped.err;
    EXPECT_FALSE(fs::exists(dir.path / "run" / "replicas"));
    r.stop_after_steps.reset();
    r.resume = true;
    const InProcessResult resumed = run_in_process(r);
    ASSERT_EQ(resumed.code, kExitOk) << resumed.err;
    EXPECT_NE(resumed.err.find("goes on as one replica"), std::string::npos) << resumed.err;
    const nlohmann::json s = summary_of(dir.path / "run");
    EXPECT_FALSE(s.contains("replicas"));
    EXPECT_EQ(s["simulated_time_s"].get<double>(), 4.0);
    // The resumed run is the plain run: replica 0 is the scene's own trajectory.
    const InProcessResult plain = run_rod(dir.path / "plain", 4.0, 1);
    ASSERT_EQ(plain.code, kExitOk) << plain.err;
    EXPECT_EQ(read_file(dir.path / "run" / kImpactCsvFileName), read_file(dir.path / "plain" / kImpactCsvFileName));
}

TEST(Replicas, ScenesThatAreNotSteadyExitTwoNamingTheOptionAndTheCause) {
    TempDir dir;
    const ShellResult r = run_shell(std::string(PEENSIM_BINARY) + " run " + PEENSIM_SOURCE_DIR +
                                    "/scenes/nozzle-gear.yaml --replicas 2 -o " + (dir.path / "n").string() + " --no-analyze --no-render");
    ASSERT_TRUE(WIFEXITED(r.status)) << r.output;
    EXPECT_EQ(WEXITSTATUS(r.status), 2) << r.output;
    EXPECT_NE(r.output.find("--replicas"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("shot sources"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("nozzle-gear.yaml"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace peensim::testing
