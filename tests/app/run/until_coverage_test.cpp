// `peensim run --until-coverage` (app/run/coverage_watch.h) and the analysis of rotating parts over
// whole turns: the run stops at the first restart point after the target, at the time the
// analysis of its own log says the target was reached; a resumed run stops where the whole run
// did, with the same log; bad targets and areas exit 2 naming them. A rotating part's window ends
// at its last whole turn, and a window shorter than a turn gives no time, only the run that would.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/analysis/analysis_format.h"
#include "app/analysis/analyze_job.h"
#include "app/run/run_job.h"
#include "support/child_process.h"
#include "support/files.h"
#include "support/shipped_scenes.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace peensim::testing {
namespace {

nlohmann::json json_of(const fs::path& path) { return nlohmann::json::parse(read_file(path)); }

std::vector<std::string> until_args(const fs::path& out) {
    return {PEENSIM_BINARY,
            "run",
            kRod,
            "-o",
            out.string(),
            "--until-coverage",
            "20 %",
            "--set",
            "process.duration=10 s",
            "--set",
            "output.checkpoint_interval=0.1 s",
            "--no-render",
            "--no-analyze",
            "--quiet"};
}

TEST(UntilCoverage, StopsWhenTheAnalysisSaysTheTargetIsReachedAndResumesToTheSameEnd) {
    TempDir dir;
    ChildProcess whole(until_args(dir.path / "whole"), (dir.path / "whole.out").string(), (dir.path / "whole.err").string());
    ASSERT_EQ(whole.wait_exit(300.0), std::optional<int>(0)) << read_file(dir.path / "whole.err");
    const auto summary = json_of(dir.path / "whole" / "summary.json");
    const auto& goal = summary["until_coverage"];
    EXPECT_EQ(goal["target"].get<double>(), 0.2);
    EXPECT_TRUE(goal["reached"].get<bool>());
    ASSERT_EQ(goal["areas"].size(), 1u);  // the rod has no regions: its peened area
    EXPECT_EQ(goal["areas"][0]["area"], "rod");
    const double reached = goal["areas"][0]["reached_at_s"].get<double>();
    const double stopped = summary["simulated_time_s"].get<double>();
    EXPECT_LE(reached, stopped);
    EXPECT_LT(stopped, 10.0);                  // not the cap
    EXPECT_LE(stopped - reached, 0.1 + 1e-9);  // the first restart point after it
    EXPECT_TRUE(summary["finished"].get<bool>());
    // The analysis of the log counts coverage the same way: reached at the same time, exactly.
    std::ostringstream out, err;
    AnalyzeOptions o;
    o.to_s = stopped;
    ASSERT_EQ(analyze_job((dir.path / "whole").string(), out, err, o), kExitOk) << err.str();
    const auto figures = json_of(dir.path / "whole" / "analysis" / "figures.json");
    EXPECT_EQ(figures["target_coverage"].get<double>(), 0.2);  // the run's own target
    const auto& rod = figures["components"][0]["time_to_target"];
    EXPECT_EQ(rod["status"], "reached");
    EXPECT_NEAR(rod["time_s"].get<double>(), reached, 1e-9 * reached);

    // Interrupted and resumed: the same end and the same log, byte for byte.
    ChildProcess stopped_run(until_args(dir.path / "parts"), (dir.path / "p.out").string(), (dir.path / "p.err").string());
    for (int k = 0; k < 3000 && !fs::exists(dir.path / "parts" / "checkpoint.bin"); ++k)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    stopped_run.signal(SIGINT);
    const auto code = stopped_run.wait_exit(120.0);
    ASSERT_TRUE(code.has_value());
    if (*code == 130) {  // caught before the end (else it had already finished: nothing to resume)
        std::vector<std::string> resume = until_args(dir.path / "parts");
        resume.push_back("--resume");
        ChildProcess resumed(resume, (dir.path / "r.out").string(), (dir.path / "r.err").string());
        ASSERT_EQ(resumed.wait_exit(300.0), std::optional<int>(0)) << read_file(dir.path / "r.err");
    }
    EXPECT_EQ(json_of(dir.path / "parts" / "summary.json")["simulated_time_s"].get<double>(), stopped);
    EXPECT_EQ(read_file(dir.path / "parts" / "impacts.csv"), read_file(dir.path / "whole" / "impacts.csv"));
}

// A run until coverage whose summary.json is lost (deleted, or copied without it) stopped at an
// end only the summary kept: the analysis reads the log to its last impact, not to the scene's
// cap (which spread the impacts over time never simulated: 2.4 s of this run over 10 s, rates 4x
// too low).
TEST(UntilCoverage, WithoutItsSummaryARunIsAnalysedToItsLastImpactNotToTheCap) {
    TempDir dir;
    ChildProcess run(until_args(dir.path / "run"), (dir.path / "run.out").string(), (dir.path / "run.err").string());
    ASSERT_EQ(run.wait_exit(300.0), std::optional<int>(0)) << read_file(dir.path / "run.err");
    const double stopped = json_of(dir.path / "run" / "summary.json")["simulated_time_s"].get<double>();
    ASSERT_LT(stopped, 10.0);
    fs::remove(dir.path / "run" / "summary.json");
    std::ostringstream out, err;
    ASSERT_EQ(analyze_job((dir.path / "run").string(), out, err), kExitOk) << err.str();
    const double to_s = json_of(dir.path / "run" / "analysis" / "figures.json")["window"]["to_s"].get<double>();
    EXPECT_LE(to_s, stopped);
    EXPECT_GT(to_s, stopped - 0.1);  // the last impact, within the run's last restart interval
    EXPECT_NE(err.str().find("no summary.json, and the run ran until coverage"), std::string::npos) << err.str();
}

TEST(UntilCoverage, BadTargetsAndAreasExitTwoNamingThem) {
    TempDir dir;
    const auto run = [&](std::vector<std::string> extra, const std::string& name) {
        std::vector<std::string> args = {PEENSIM_BINARY, "run", kRod, "-o", (dir.path / name).string(), "--no-render", "--quiet"};
        args.insert(args.end(), extra.begin(), extra.end());
        ChildProcess p(args, (dir.path / (name + ".out")).string(), (dir.path / (name + ".err")).string());
        const auto code = p.wait_exit(60.0);
        return std::make_pair(code.value_or(-1), read_file(dir.path / (name + ".err")));
    };
    // Named as the option given (it was reported as a --set of the scene field it sets).
    auto [code1, err1] = run({"--until-coverage", "150 %"}, "over");
    EXPECT_EQ(code1, 2) << err1;
    EXPECT_NE(err1.find("error: --until-coverage: expected a coverage above 0 and at most 100 %"), std::string::npos) << err1;
    EXPECT_EQ(err1.find("--set"), std::string::npos) << err1;
    auto [code0, err0] = run({"--until-coverage", "0%"}, "zero");
    EXPECT_EQ(code0, 2) << err0;
    EXPECT_NE(err0.find("error: --until-coverage: expected a coverage above 0 and at most 100 % (e.g. 98 % or 0.98), got '0%'"),
              std::string::npos)
        << err0;
    auto [code2, err2] = run({"--until-coverage", "90 %", "--set", "process.until_coverage_of=[rod/tip]"}, "region");
    EXPECT_EQ(code2, 2) << err2;
    EXPECT_NE(err2.find("rod/tip"), std::string::npos) << err2;
    auto [code3, err3] = run({"--until-coverage", "90 %", "--set", "process.until_coverage_of=[chamber]"}, "no-yield");
    EXPECT_EQ(code3, 2) << err3;
    EXPECT_NE(err3.find("chamber"), std::string::npos) << err3;
    EXPECT_FALSE(fs::exists(dir.path / "over" / "impacts.csv"));
    // An area twice, and a region coverage does not count (the gear's bore, `exclude: true`): refused
    // before anything is written (the run once started, waited twice for the one, and failed late
    // on the other, leaving its first files behind).
    const std::string gear = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rotating-gear.yaml";
    const auto run_gear = [&](const std::string& of, const std::string& name, const std::vector<std::string>& extra = {}) {
        std::vector<std::string> args = {PEENSIM_BINARY,
                                         "run",
                                         gear,
                                         "-o",
                                         (dir.path / name).string(),
                                         "--no-render",
                                         "--quiet",
                                         "--until-coverage",
                                         "8 %",
                                         "--set",
                                         "process.until_coverage_of=" + of};
        args.insert(args.end(), extra.begin(), extra.end());
        ChildProcess p(args, (dir.path / (name + ".out")).string(), (dir.path / (name + ".err")).string());
        const auto code = p.wait_exit(120.0);
        return std::make_pair(code.value_or(-1), read_file(dir.path / (name + ".err")));
    };
    auto [code4, err4] = run_gear("[gear/tooth-5, gear/tooth-5]", "twice");
    EXPECT_EQ(code4, 2) << err4;
    EXPECT_NE(err4.find("process.until_coverage_of: 'gear/tooth-5' is listed twice; expected each area once"), std::string::npos) << err4;
    auto [code5, err5] = run_gear("[gear/bore]", "excluded");
    EXPECT_EQ(code5, 2) << err5;
    EXPECT_NE(err5.find("process.until_coverage_of: region 'gear/bore' is excluded (`exclude: true`)"), std::string::npos) << err5;
    auto [code6, err6] = run_gear("[gear/tooth-99]", "unknown");
    EXPECT_EQ(code6, 2) << err6;
    EXPECT_NE(err6.find("tooth-19 (from --set"), std::string::npos) << err6;  // the counted regions, the bore not among them
    EXPECT_EQ(err6.find("bore"), std::string::npos) << err6;
    for (const char* name : {"twice", "excluded", "unknown"}) EXPECT_FALSE(fs::exists(dir.path / name)) << name;
    // The bore counted (not excluded) but out of every shot's reach (the axle fills it): known only
    // once the reach of every sample is, after the run's directory was made; the fresh run leaves
    // nothing behind (it once left its scene.resolved.yaml and impacts.csv.partial) and names it.
    const auto run_counted_bore = [&](const std::string& of, const std::string& name) {
        return run_gear(of, name, {"--set", "components[gear].regions[1].exclude=false", "--set", "process.duration=3 s"});
    };
    auto [code7, err7] = run_counted_bore("[gear/bore]", "out-of-reach");
    EXPECT_EQ(code7, 2) << err7;
    EXPECT_NE(err7.find("process.until_coverage_of: 'gear/bore' has no surface a shot can reach"), std::string::npos) << err7;
    EXPECT_FALSE(fs::exists(dir.path / "out-of-reach"));
    // Beside an area that can be reached it is said so, and the run goes on without it.
    auto [code8, err8] = run_counted_bore("[gear/bore, gear/tooth-3]", "with-a-tooth");
    EXPECT_EQ(code8, 0) << err8;
    EXPECT_NE(err8.find("note: until_coverage_of: no shot can reach gear/bore: not waited for"), std::string::npos) << err8;
}

// The rotating gear turns at 30 rpm (a turn: 2 s). 5 s: analysed over 2 whole turns; 1 s: half a
// turn, no time at all.
TEST(RotatingAnalysis, WholeTurnsAndNoTimeFromLessThanATurn) {
    TempDir dir;
    RunOptions o;
    o.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rotating-gear.yaml";
    o.output_dir = dir.path.string();
    o.overrides = {"process.duration=5 s", "components[gear].motion.speed=30 rpm"};
    o.progress = false;
    o.analyze = false;
    std::ostringstream out, err;
    ASSERT_EQ(run_job(o, out, err), kExitOk) << err.str();
    ASSERT_EQ(analyze_job(dir.path.string(), out, err), kExitOk) << err.str();
    auto figures = json_of(dir.path / "analysis" / "figures.json");
    EXPECT_NEAR(figures["window"]["turn_s"].get<double>(), 2.0, 1e-12);
    EXPECT_NEAR(figures["window"]["to_s"].get<double>(), 4.0, 1e-9);
    EXPECT_EQ(figures["window"]["asked_to_s"].get<double>(), 5.0);
    std::string report = read_file(dir.path / "analysis" / "report.md");
    EXPECT_NE(report.find("Analysed over 2 whole turns of the rotating part"), std::string::npos) << report;
    EXPECT_NE(report.find("A run of 6 s (3 turns) uses every impact"), std::string::npos) << report;
    // The title says what the run changed.
    EXPECT_NE(report.find("(run with --set process.duration=5 s --set components[gear].motion.speed=30 rpm)"), std::string::npos)
        << report.substr(0, 300);
    AnalyzeOptions half;
    half.to_s = 1.0;
    ASSERT_EQ(analyze_job(dir.path.string(), out, err, half), kExitOk) << err.str();
    figures = json_of(dir.path / "analysis" / "figures.json");
    const auto& gear = figures["components"][0];
    for (const char* key : {"time_to_target", "time_to_target_everywhere"}) {
        EXPECT_EQ(gear[key]["status"], "too_short") << key;
        EXPECT_NEAR(gear[key]["run_for_s"].get<double>(), 2.0, 1e-9) << key;
    }
    report = read_file(dir.path / "analysis" / "report.md");
    EXPECT_NE(report.find("**The window is 0.5 of a turn of the rotating part"), std::string::npos) << report;
    EXPECT_NE(report.find("Run at least 2 s (a whole turn)"), std::string::npos) << report;
}

// The shipped rotating gear run with these overrides (no analysis, no animation): its summary.json.
nlohmann::json run_rotating_gear(const TempDir& dir, std::vector<std::string> overrides) {
    RunOptions o;
    o.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rotating-gear.yaml";
    o.output_dir = dir.path.string();
    o.overrides = std::move(overrides);
    o.progress = false;
    o.analyze = false;
    std::ostringstream out, err;
    EXPECT_EQ(run_job(o, out, err), kExitOk) << err.str();
    return json_of(dir.path / "summary.json");
}

// A run until coverage of a turning part ends where its target was reached, within a turn (37 rpm:
// a turn of 1.62 s, never a whole number of them at a restart point of 0.1 s). Its analysis keeps
// that end: every area reached when the run says, and no advice to run until coverage. Cut back to
// whole turns (as before), the report forecast the slowest tooth and advised a run to coverage.
TEST(RotatingAnalysis, ARunUntilCoverageIsAnalysedToItsEndNotCutToWholeTurns) {
    TempDir dir;
    std::ostringstream out, err;
    const auto summary = run_rotating_gear(dir, {"process.duration=60 s", "process.until_coverage=5 %",
                                                 "components[gear].motion.speed=37 rpm", "output.checkpoint_interval=0.1 s"});
    ASSERT_TRUE(summary["until_coverage"]["reached"].get<bool>());
    const double stopped = summary["simulated_time_s"].get<double>();
    double last_reached = 0.0;  // s: when the last watched area reached 5 %
    for (const auto& a : summary["until_coverage"]["areas"]) last_reached = std::max(last_reached, a["reached_at_s"].get<double>());
    const double turn = 60.0 / 37.0;
    ASSERT_GT(stopped / turn - std::floor(stopped / turn), 1e-6);  // the run ended within a turn

    ASSERT_EQ(analyze_job(dir.path.string(), out, err), kExitOk) << err.str();
    const auto figures = json_of(dir.path / "analysis" / "figures.json");
    EXPECT_EQ(figures["window"]["to_s"].get<double>(), stopped);
    EXPECT_TRUE(figures["window"]["ends_at_target"].get<bool>());
    const auto& gear = figures["components"][0];
    EXPECT_EQ(gear["time_to_target"]["status"], "reached");
    EXPECT_EQ(gear["time_to_target_everywhere"]["status"], "reached");
    EXPECT_NEAR(gear["time_to_target_everywhere"]["time_s"].get<double>(), last_reached, 1e-9 * last_reached);
    const std::string report = read_file(dir.path / "analysis" / "report.md");
    EXPECT_EQ(report.find("--until-coverage \""), std::string::npos) << report;
    EXPECT_NE(report.find("The run peened until every area reached its target (`--until-coverage`) and ended there"), std::string::npos)
        << report;

    // Analysed at a higher target than the run reached, the window is cut to whole turns as any
    // run's: the forecasts read whole turns.
    AnalyzeOptions higher;
    higher.target_coverage = 0.5;
    ASSERT_EQ(analyze_job(dir.path.string(), out, err, higher), kExitOk) << err.str();
    const auto cut = json_of(dir.path / "analysis" / "figures.json");
    EXPECT_FALSE(cut["window"]["ends_at_target"].get<bool>());
    EXPECT_NEAR(cut["window"]["to_s"].get<double>(), std::floor(stopped / turn) * turn, 1e-9);
    // So is a window that starts later (its coverage is not the run's).
    AnalyzeOptions later;
    later.from_s = 1.0;
    ASSERT_EQ(analyze_job(dir.path.string(), out, err, later), kExitOk) << err.str();
    const auto from = json_of(dir.path / "analysis" / "figures.json");
    EXPECT_FALSE(from["window"]["ends_at_target"].get<bool>());
    EXPECT_NEAR(from["window"]["to_s"].get<double>(), 1.0 + std::floor((stopped - 1.0) / turn) * turn, 1e-9);
}

// A run until coverage of some areas only (`until_coverage_of`) is still analysed over whole turns,
// for the forecasts of the areas it did not watch; a watched area that reached the target in the
// part of a turn left out takes its time from the run (the dents the run counted are those the
// analysis would count over the whole log: the same time to the bit), not a forecast from the
// shorter window that contradicts it.
TEST(RotatingAnalysis, AWatchedAreaReachedAfterTheLastWholeTurnTakesItsTimeFromTheRun) {
    TempDir dir;
    std::ostringstream out, err;
    const auto summary =
        run_rotating_gear(dir, {"process.duration=60 s", "process.until_coverage=5 %", "process.until_coverage_of=[gear/tooth-3, gear]",
                                "components[gear].motion.speed=37 rpm", "output.checkpoint_interval=0.1 s"});
    ASSERT_TRUE(summary["until_coverage"]["reached"].get<bool>());
    const double stopped = summary["simulated_time_s"].get<double>();
    std::map<std::string, double> reached_at;  // s, per watched area
    for (const auto& a : summary["until_coverage"]["areas"]) reached_at[a["area"].get<std::string>()] = a["reached_at_s"].get<double>();
    const double turn = 60.0 / 37.0, cut_s = std::floor(stopped / turn) * turn;
    ASSERT_GT(reached_at.at("gear/tooth-3"), cut_s) << "the case needs the tooth reached after the last whole turn";

    ASSERT_EQ(analyze_job(dir.path.string(), out, err), kExitOk) << err.str();
    const auto figures = json_of(dir.path / "analysis" / "figures.json");
    EXPECT_FALSE(figures["window"]["ends_at_target"].get<bool>());
    EXPECT_NEAR(figures["window"]["to_s"].get<double>(), cut_s, 1e-9);
    const auto region = [](const nlohmann::json& part, const std::string& name) {
        for (const auto& r : part["regions"])
            if (r["region"] == name) return r["time_to_target"];
        return nlohmann::json();
    };
    const auto& gear = figures["components"][0];
    const auto tooth3 = region(gear, "tooth-3");
    EXPECT_EQ(tooth3["status"], "reached");
    EXPECT_TRUE(tooth3.value("seen_in_run", false));
    EXPECT_EQ(tooth3["time_s"].get<double>(), reached_at.at("gear/tooth-3"));
    EXPECT_LT(tooth3["coverage_now"].get<double>(), 0.05);  // the window's, where it had not
    // The teeth the run did not watch keep the window's own figures.
    for (const auto& r : gear["regions"]) {
        if (r["region"] != "tooth-3") {
            EXPECT_FALSE(r["time_to_target"].value("seen_in_run", false)) << r["region"];
        }
    }
    const std::string report = read_file(dir.path / "analysis" / "report.md");
    EXPECT_NE(report.find("reached at " + fmt(reached_at.at("gear/tooth-3")) + " s (the run's; after the window)"), std::string::npos)
        << report;
    EXPECT_NE(report.find("it counted gear/tooth-3 reaching it at"), std::string::npos) << report;
    // No longer run to advise: it would end where this one did.
    EXPECT_EQ(report.find("uses every impact"), std::string::npos) << report;
    // Everywhere is still a forecast (the teeth not watched), never before a time the run saw.
    const auto& everywhere = gear["time_to_target_everywhere"];
    ASSERT_EQ(everywhere["status"], "forecast");
    EXPECT_GE(everywhere["time_s"].get<double>(), reached_at.at("gear/tooth-3"));
    // The run to every region it advises watches every region, not the scene's one tooth.
    EXPECT_NE(report.find("--until-coverage \"5 %\""), std::string::npos) << report;
    EXPECT_NE(report.find("--set \"process.until_coverage_of=[]\""), std::string::npos) << report;

    // The analysis' own count over the whole log (--to its end) gives the run's time to the bit.
    AnalyzeOptions whole;
    whole.to_s = stopped;
    ASSERT_EQ(analyze_job(dir.path.string(), out, err, whole), kExitOk) << err.str();
    const auto own = region(json_of(dir.path / "analysis" / "figures.json")["components"][0], "tooth-3");
    EXPECT_EQ(own["status"], "reached");
    EXPECT_FALSE(own.value("seen_in_run", false));
    EXPECT_EQ(own["time_s"].get<double>(), reached_at.at("gear/tooth-3"));
    // At another target than the run's, its times are not the answer: the window's forecasts.
    AnalyzeOptions other;
    other.target_coverage = 0.06;
    ASSERT_EQ(analyze_job(dir.path.string(), out, err, other), kExitOk) << err.str();
    EXPECT_FALSE(region(json_of(dir.path / "analysis" / "figures.json")["components"][0], "tooth-3").value("seen_in_run", false));
}

// Every region reached the target, the last (tooth-16, watched) in the part of a turn the window
// leaves out: everywhere is reached then, at that tooth's time, not forecast before it (the case an
// independent test found: "everywhere 12.04 s, forecast" beside tooth-16 "reached at 12.09 s").
TEST(RotatingAnalysis, EverywhereIsReachedWhenTheLastRegionIsSeenReachedByTheRun) {
    TempDir dir;
    std::ostringstream out, err;
    run_rotating_gear(dir,
                      {"process.duration=60 s", "process.until_coverage=8 %", "process.until_coverage_of=[gear/tooth-8, gear/tooth-16]"});
    ASSERT_EQ(analyze_job(dir.path.string(), out, err), kExitOk) << err.str();
    const auto figures = json_of(dir.path / "analysis" / "figures.json");
    const auto& gear = figures["components"][0];
    double latest = 0.0;
    std::string last;
    for (const auto& r : gear["regions"]) {
        const auto& t = r["time_to_target"];
        if (t["status"] == "none") continue;  // the bore
        ASSERT_EQ(t["status"], "reached") << r["region"] << ": the case needs every region reached";
        if (t["time_s"].get<double>() > latest) latest = t["time_s"].get<double>(), last = r["region"].get<std::string>();
    }
    ASSERT_GT(latest, figures["window"]["to_s"].get<double>()) << "the case needs the last region reached after the window";
    const auto& everywhere = gear["time_to_target_everywhere"];
    EXPECT_EQ(everywhere["status"], "reached");
    EXPECT_EQ(everywhere["time_s"].get<double>(), latest);
    EXPECT_EQ(gear["slowest_region"], last);
}

}  // namespace
}  // namespace peensim::testing
