#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "output/summary_json.h"
#include "output/summary_text.h"

namespace peensim {
namespace {

namespace fs = std::filesystem;

RunSummary example_summary() {
    RunSummary s;
    s.scene_file = "scenes/gear.yaml";
    s.scene_hash = "3fa9c2e01b7d44aa";
    s.scheme = "symplectic_euler";
    s.finished = true;
    s.simulated_time_s = 0.5;
    s.duration_s = 0.5;
    s.wall_time_s = 12.25;
    s.steps = 500000;
    s.shot_steps = 2500000000ull;
    s.shot_steps_per_s = 2.0408163265306123e8;
    s.sim_seconds_per_wall_second = 0.04081632653061224;
    s.shot_count = 5000;
    s.shot_lost = 3;
    s.impacts_per_component = {{"gear", 123456}, {"chamber", 789}};
    s.slow_contacts_per_component = {{"gear", 12}, {"chamber", 0}};
    s.impact_speed_m_per_s = 0.05;
    SpeedHistogram gear;
    for (int i = 1; i <= 100; ++i) gear.add(0.1 * i);  // m/s
    s.normal_speed = {normal_speed_stats("gear", gear), normal_speed_stats("chamber", SpeedHistogram())};
    s.health_counters = {{"escaped_shots", 3}, {"non_finite_velocity", 0}};
    s.stage_times = {{"detectContacts", 7.5}, {"integrateShots", 1.25}};
    s.peak_memory_bytes = 123456789;
    return s;
}

TEST(SummaryJsonTest, ParsesBackWithUnitKeysAndValues) {
    const RunSummary s = example_summary();
    const std::string text = summary_to_json(s);
    EXPECT_EQ(text.back(), '\n');
    EXPECT_NE(text.find("\n  \"scene_file\""), std::string::npos);  // pretty-printed

    const auto j = nlohmann::json::parse(text);
    EXPECT_EQ(j.at("scene_file"), "scenes/gear.yaml");
    EXPECT_EQ(j.at("scene_hash"), "3fa9c2e01b7d44aa");
    EXPECT_EQ(j.at("scheme"), "symplectic_euler");
    EXPECT_EQ(j.at("finished"), true);
    EXPECT_EQ(j.at("simulated_time_s").get<double>(), 0.5);
    EXPECT_EQ(j.at("duration_s").get<double>(), 0.5);
    EXPECT_EQ(j.at("wall_time_s").get<double>(), 12.25);
    EXPECT_EQ(j.at("steps").get<std::uint64_t>(), 500000u);
    EXPECT_EQ(j.at("shot_steps").get<std::uint64_t>(), 2500000000ull);
    EXPECT_EQ(j.at("shot_steps_per_s").get<double>(), s.shot_steps_per_s);
    EXPECT_EQ(j.at("sim_seconds_per_wall_second").get<double>(), s.sim_seconds_per_wall_second);
    EXPECT_EQ(j.at("shot_count").get<std::uint64_t>(), 5000u);
    EXPECT_EQ(j.at("shot_lost").get<std::uint64_t>(), 3u);
    EXPECT_EQ(j.at("peak_memory_bytes").get<std::uint64_t>(), 123456789u);

    const auto& impacts = j.at("impacts_per_component");
    ASSERT_EQ(impacts.size(), 2u);
    EXPECT_EQ(impacts[0].at("component"), "gear");
    EXPECT_EQ(impacts[0].at("impacts").get<std::uint64_t>(), 123456u);
    EXPECT_EQ(impacts[1].at("component"), "chamber");
    const auto& slow = j.at("slow_contacts_per_component");
    ASSERT_EQ(slow.size(), 2u);
    EXPECT_EQ(slow[0].at("component"), "gear");
    EXPECT_EQ(slow[0].at("slow_contacts").get<std::uint64_t>(), 12u);
    EXPECT_EQ(slow[1].at("slow_contacts").get<std::uint64_t>(), 0u);
    EXPECT_EQ(j.at("impact_speed_mps").get<double>(), 0.05);

    const auto& speeds = j.at("normal_speed");
    ASSERT_EQ(speeds.size(), 2u);
    const auto& gear = speeds[0];
    EXPECT_EQ(gear.at("component"), "gear");
    EXPECT_EQ(gear.at("count").get<std::uint64_t>(), 100u);
    EXPECT_NEAR(gear.at("mean_normal_speed_mps").get<double>(), 5.05, 1e-12);
    EXPECT_NEAR(gear.at("p10_normal_speed_mps").get<double>(), 1.0,
                0.0011);  // one bin width + rounding
    EXPECT_NEAR(gear.at("p50_normal_speed_mps").get<double>(), 5.0,
                0.0011);  // one bin width + rounding
    EXPECT_NEAR(gear.at("p90_normal_speed_mps").get<double>(), 9.0,
                0.0011);  // one bin width + rounding
    EXPECT_EQ(gear.at("max_normal_speed_mps").get<double>(), 10.0);
    // A component without impacts has no statistics: null, not a made-up 0.
    EXPECT_EQ(speeds[1].at("count").get<std::uint64_t>(), 0u);
    EXPECT_TRUE(speeds[1].at("mean_normal_speed_mps").is_null());
    EXPECT_TRUE(speeds[1].at("p50_normal_speed_mps").is_null());

    EXPECT_EQ(j.at("health_counters").at("escaped_shots").get<std::uint64_t>(), 3u);
    EXPECT_EQ(j.at("health_counters").at("non_finite_velocity").get<std::uint64_t>(), 0u);
    EXPECT_EQ(j.at("step_stage_time_s").at("detectContacts").get<double>(), 7.5);
    EXPECT_EQ(j.at("step_stage_time_s").at("integrateShots").get<double>(), 1.25);
}

TEST(SummaryJsonTest, KeysKeepTheDocumentedOrder) {
    const std::string text = summary_to_json(example_summary());
    EXPECT_LT(text.find("\"detectContacts\""), text.find("\"integrateShots\""));
    EXPECT_LT(text.find("\"scene_file\""), text.find("\"peak_memory_bytes\""));
}

TEST(SummaryJsonTest, WriteSummaryWritesTheJsonFile) {
    std::string pattern = (fs::temp_directory_path() / "peensim-summary-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    const fs::path path = fs::path(pattern) / "summary.json";
    const RunSummary s = example_summary();
    write_summary(path.string(), s);
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), summary_to_json(s));
    fs::remove_all(pattern);
}

TEST(SummaryTextTest, AlignedLinesWithTheKeyNumbers) {
    RunSummary s = example_summary();
    const std::string text = summary_to_text(s);
    EXPECT_NE(text.find("0.5 s of 0.5 s (finished)"), std::string::npos) << text;
    EXPECT_NE(text.find("impacts gear"), std::string::npos) << text;
    EXPECT_NE(text.find("123456"), std::string::npos) << text;
    EXPECT_NE(text.find("max 10.000 m/s"), std::string::npos) << text;
    EXPECT_NE(text.find("escaped_shots 3"), std::string::npos) << text;
    EXPECT_NE(text.find("slow contacts"), std::string::npos) << text;
    EXPECT_NE(text.find("gear 12 (landings slower than 0.05 m/s)"), std::string::npos) << text;
    EXPECT_EQ(text.find("non_finite_velocity"), std::string::npos) << text;  // zero: not listed
    EXPECT_NE(text.find("117.7 MiB"), std::string::npos) << text;

    // Values start in one column.
    std::istringstream lines(text);
    std::string line;
    std::getline(lines, line);  // title
    std::size_t column = std::string::npos;
    while (std::getline(lines, line)) {
        const std::size_t value = line.find_first_not_of(' ', line.find("  ", 2));
        if (column == std::string::npos) column = value;
        EXPECT_EQ(value, column) << line;
    }

    s.finished = false;
    s.health_counters = {{"escaped_shots", 0}};
    const std::string interrupted = summary_to_text(s);
    EXPECT_NE(interrupted.find("(interrupted)"), std::string::npos) << interrupted;
    EXPECT_NE(interrupted.find("all zero"), std::string::npos) << interrupted;
}

// A run until coverage that finished without reaching the target stopped at its duration, which
// may be a quick look's: the line says so and how to raise it. Reached, or interrupted, it does not.
TEST(SummaryTextTest, UntilCoverageNotReachedAtTheEndSaysTheDurationCappedIt) {
    RunSummary s = example_summary();
    s.duration_s = 5.0;
    RunSummary::CoverageGoal goal;
    goal.areas = {{"gear/tooth-1", std::nan(""), 0.0301}, {"gear/tooth-0", std::nan(""), 0.0158}, {"gear/tooth-2", 3.5, 0.98}};
    s.until_coverage = goal;
    const std::string capped = summary_to_text(s);
    // The least covered of those not there yet is named, wherever it is in the list.
    EXPECT_NE(capped.find("98 % reached in 1 of 3 areas by the cap, process.duration = 5 s (raise it with --set "
                          "\"process.duration=...\"); not yet: gear/tooth-0 at 1.58 %, ..."),
              std::string::npos)
        << capped;
    s.finished = false;
    const std::string interrupted = summary_to_text(s);
    EXPECT_NE(interrupted.find("98 % reached in 1 of 3 areas; not yet: gear/tooth-0"), std::string::npos) << interrupted;
    s.finished = true;
    s.until_coverage->areas[0].reached_at_s = 4.0;
    s.until_coverage->areas[1].reached_at_s = 4.5;
    s.until_coverage->reached = true;
    const std::string reached = summary_to_text(s);
    EXPECT_NE(reached.find("98 % reached everywhere watched (3 areas) at 4.5 s, last gear/tooth-0"), std::string::npos) << reached;
    EXPECT_EQ(reached.find("by the cap"), std::string::npos) << reached;
}

}  // namespace
}  // namespace peensim
