// `peensim sweep` (app/sweep/sweep_plan.h, sweep_job.h, sweep_compare.h): the plan (axes, grid order,
// names, seeds, refusals), the statistics (Student's t interval, the verdict), and sweeps of the rod
// scene run by the real binary: each run byte-identical to running it alone, whatever the number of
// jobs; a finished run never rerun; a failing run retried once and reported; the comparison's
// figures those of the runs' own analyses.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/run/run_job.h"
#include "app/sweep/sweep_checks.h"
#include "app/sweep/sweep_compare.h"
#include "app/sweep/sweep_job.h"
#include "app/sweep/sweep_plan.h"
#include "common/input_error.h"
#include "support/child_process.h"
#include "support/files.h"
#include "support/mpirun_environment.h"
#include "support/shell_command.h"
#include "support/shipped_scenes.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace peensim::testing {
namespace {

TEST(SweepPlan, AxesSplitAtTopLevelCommasOnly) {
    const SweepAxis speed = parse_sweep_axis("components[gear].motion.speed=15 rpm, 30 rpm,60 rpm");
    EXPECT_EQ(speed.path, "components[gear].motion.speed");
    EXPECT_EQ(speed.values, (std::vector<std::string>{"15 rpm", "30 rpm", "60 rpm"}));
    const SweepAxis gravity = parse_sweep_axis("process.gravity=[0, 0, -9.81],[0, -9.81, 0]");
    EXPECT_EQ(gravity.values, (std::vector<std::string>{"[0, 0, -9.81]", "[0, -9.81, 0]"}));
    for (const char* bad : {"speed", "=1,2", "shot.diameter=1 mm,,2 mm", "process.gravity=[0, 0, -9.81"}) {
        EXPECT_THROW(parse_sweep_axis(bad), InputError) << bad;
    }
}

TEST(SweepPlan, EveryCombinationFirstAxisSlowestTimesTheSeeds) {
    const SweepPlan plan =
        plan_sweep({parse_sweep_axis("components[gear].motion.speed=30 rpm,60 rpm"), parse_sweep_axis("shot.diameter=1 mm,2 mm,3 mm")}, 2,
                   7, {"process.duration=1 s"}, "out");
    ASSERT_EQ(plan.variants.size(), 6u);
    EXPECT_EQ(plan.variants[0].name, "speed-30rpm_diameter-1mm");
    EXPECT_EQ(plan.variants[1].name, "speed-30rpm_diameter-2mm");
    EXPECT_EQ(plan.variants[3].name, "speed-60rpm_diameter-1mm");
    ASSERT_EQ(plan.runs.size(), 12u);
    const SweepRun& r = plan.runs[3];  // variant 1, second seed
    EXPECT_EQ(r.variant, 1u);
    EXPECT_EQ(r.replicate, 1);
    EXPECT_EQ(r.seed, 8u);
    EXPECT_EQ(r.dir, "out/speed-30rpm_diameter-2mm/s1");
    EXPECT_EQ(r.overrides, (std::vector<std::string>{"process.duration=1 s", "components[gear].motion.speed=30 rpm", "shot.diameter=2 mm",
                                                     "process.seed=8"}));
    // Names that would collide are numbered ("a b" and "ab" are two texts; "1 mm" and "1mm" one
    // length, refused); no axis: one variant, the scene itself.
    const SweepPlan close = plan_sweep({parse_sweep_axis("name=a b,ab")}, 1, 1, {}, "o");
    EXPECT_EQ(close.variants[1].name, "name-ab.2");
    // A file by its file name; two of one name in two folders numbered.
    const SweepPlan meshes =
        plan_sweep({parse_sweep_axis("components[rod].mesh=/tmp/study/rod.step,../parts/thin rod.stl,/tmp/old/rod.step")}, 1, 1, {}, "o");
    EXPECT_EQ(meshes.variants[0].name, "mesh-rod.step");
    EXPECT_EQ(meshes.variants[1].name, "mesh-thinrod.stl");
    EXPECT_EQ(meshes.variants[2].name, "mesh-rod.step.2");
    EXPECT_THROW(plan_sweep({parse_sweep_axis("shot.diameter=1 mm,1mm")}, 1, 1, {}, "o"), InputError);
    EXPECT_EQ(plan_sweep({}, 3, 1, {}, "o").runs.size(), 3u);
    EXPECT_EQ(plan_sweep({}, 1, 1, {}, "o").variants[0].name, "base");
    EXPECT_THROW(plan_sweep({parse_sweep_axis("shot.diameter=1 mm"), parse_sweep_axis("shot.diameter=2 mm")}, 1, 1, {}, "o"), InputError);
    EXPECT_THROW(plan_sweep({}, 0, 1, {}, "o"), InputError);
}

// The bounds are checked from the counts, before a variant is built (3.2 M runs refused at once);
// a value given twice, or the same value written two ways, is refused naming it.
TEST(SweepPlan, BoundsAndDuplicatesAreRefusedBeforeTheGridIsBuilt) {
    const auto values = [](int n, const std::string& unit) {
        std::string s;
        for (int k = 1; k <= n; ++k) s += (k > 1 ? "," : "") + std::to_string(k) + unit;
        return s;
    };
    const auto problem = [](const auto& plan) {
        try {
            plan();
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    std::vector<SweepAxis> grid;
    for (const char* path : {"process.seed", "shot.count", "process.duration", "shot.diameter", "accuracy.impact_speed"})
        grid.push_back(parse_sweep_axis(std::string(path) + "=" + values(20, "")));
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_NE(problem([&] { plan_sweep(grid, 1, 1, {}, "o"); }).find("a grid of 20 x 20 x 20 x 20 x 20 values x 1 seed make 3200000 runs"),
              std::string::npos);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
    EXPECT_NE(
        problem([&] { parse_sweep_axis("process.seed=" + values(1001, "")); }).find("1001 values; expected at most 1000 values per --vary"),
        std::string::npos);
    EXPECT_NO_THROW(plan_sweep({parse_sweep_axis("process.seed=" + values(1000, ""))}, 10, 1, {}, "o"));  // 10 000 runs: the bound
    EXPECT_NE(problem([&] { plan_sweep({parse_sweep_axis("process.seed=" + values(1000, ""))}, 11, 1, {}, "o"); }).find("make 11000 runs"),
              std::string::npos);
    EXPECT_NE(problem([&] { plan_sweep({}, 1001, 1, {}, "o"); }).find("--seeds: expected 1 to 1000 replicates per variant, got '1001'"),
              std::string::npos);
    // Twice, and written two ways: lengths, whole numbers, vectors, maps in another key order.
    EXPECT_NE(problem([&] {
                  plan_sweep({parse_sweep_axis("process.seed=1,2,1")}, 1, 1, {}, "o");
              }).find("--vary: process.seed: the value '1' is given twice; expected each value once"),
              std::string::npos);
    for (const char* same : {"shot.diameter=1 mm,1mm", "shot.diameter=2 mm,0.002 m", "shot.count=64,6.4e1", "shot.count=64,+64",
                             "process.gravity=[0, 0, -9.81],[0,0,-9.81 m/s2]",
                             "components[rod].motion={type: rotating, speed: 10 rpm},"
                             "{speed: 10 rpm, type: rotating}"})
        EXPECT_NE(problem([&] { plan_sweep({parse_sweep_axis(same)}, 1, 1, {}, "o"); }).find("is the value"), std::string::npos) << same;
    EXPECT_NO_THROW(
        plan_sweep({parse_sweep_axis("process.seed=9007199254740993,9007199254740992")}, 1, 1, {}, "o"));  // beyond 2^53: as text
    // Listed variants: a bad name, or two setting the same, blamed on the variant's own line.
    const auto variant = [](const std::string& name, const std::string& count, int line) {
        SweepVariant v;
        v.name = name;
        v.set = {{"shot.count", count}};
        v.origin = SourceLocation{"study.yaml", line, 5};
        v.field = "variants[" + std::to_string(line - 4) + "]";
        return v;
    };
    const SweepVariant a = variant("a", "64", 4);
    SweepVariant b = variant("b", "6.4e1", 5);
    EXPECT_NE(problem([&] {
                  plan_sweep_variants({a, b}, 1, 1, {}, "o");
              }).find("study.yaml:5:5: variants[1].set: variant 'b' sets the same values as variant 'a'"),
              std::string::npos);
    b.set = {{"shot.count", "128"}};
    b.name = "../b";
    EXPECT_NE(problem([&] {
                  plan_sweep_variants({a, b}, 1, 1, {}, "o");
              }).find("study.yaml:5:5: variants[1].name: variant name '../b'"),
              std::string::npos);
}

// A variant that sets process.seed has its replicates start there (before, every variant ran the
// scene's seed: the variant's value was overridden by the replicate's). Read as the runs read it.
TEST(SweepPlan, AVariantThatSetsTheSeedHasItsReplicatesStartThere) {
    SweepPlan plan = plan_sweep({parse_sweep_axis("process.seed=3,7")}, 2, 1, {"process.duration=10 ms"}, "o");
    std::ostringstream progress;
    check_sweep_variants(kRod, plan, {}, progress);
    ASSERT_EQ(plan.runs.size(), 4u);
    EXPECT_EQ(plan.runs[0].seed, 3u);
    EXPECT_EQ(plan.runs[1].seed, 4u);
    EXPECT_EQ(plan.runs[3].seed, 8u);
    EXPECT_EQ(plan.runs[3].overrides.back(), "process.seed=8");
    EXPECT_EQ(plan.runs[3].dir, "o/seed-7/s1");
    // A variant leaving the seed alone keeps the scene's (rod.yaml: 1).
    SweepPlan other = plan_sweep({parse_sweep_axis("shot.count=64,128")}, 2, 1, {"process.duration=10 ms"}, "o");
    check_sweep_variants(kRod, other, {}, progress);
    EXPECT_EQ(other.runs[3].seed, 2u);
    EXPECT_EQ(progress.str(), "");  // a few variants: no progress lines
}

TEST(SweepStatistics, StudentsIntervalAndTheVerdict) {
    // Two values 1 and 3: mean 2, sd sqrt(2), interval t(0.975, 1) sd / sqrt(2) = 12.706.
    const SweepFigure two = mean_with_ci95({1.0, 3.0});
    EXPECT_DOUBLE_EQ(*two.mean, 2.0);
    EXPECT_NEAR(*two.ci95, 12.7062, 1e-4);
    // Ten values 0..9: sd 3.02765, interval 2.262157 * 3.02765 / sqrt(10) = 2.165851.
    std::vector<double> ten;
    for (int k = 0; k < 10; ++k) ten.push_back(k);
    EXPECT_NEAR(*mean_with_ci95(ten).ci95, 2.165851, 1e-6);
    EXPECT_FALSE(mean_with_ci95({5.0}).ci95);
    EXPECT_EQ(*mean_with_ci95({5.0, NAN}).mean, 5.0);  // a missing figure is left out
    // Differs when |a - b| exceeds sqrt(ci_a^2 + ci_b^2) = 5.
    EXPECT_EQ(compare_figures({10.0, 3.0, ""}, {4.0, 4.0, ""}).verdict, "differs");
    EXPECT_EQ(compare_figures({8.0, 3.0, ""}, {4.0, 4.0, ""}).verdict, "within noise");
    EXPECT_EQ(*compare_figures({8.0, 3.0, ""}, {4.0, 4.0, ""}).delta, 4.0);
    EXPECT_EQ(compare_figures({8.0, std::nullopt, ""}, {4.0, 4.0, ""}).verdict, "-");
}

// A small sweep of the rod: two shot counts, 20 ms, one seed.

// The comparison reads what decides from each run's figures.json: the slowest region's time, the
// time everywhere, uniformity and the share below the target, each with its interval and verdict.
// Two variants whose whole-part times agree but whose slowest tooth halves must differ there.
void write_fake_run(const fs::path& dir, double whole_s, double slow_tooth_s, double everywhere_s, double uniformity, double share_below,
                    const std::string& too_short = "") {
    fs::create_directories(dir / "analysis");
    std::ofstream(dir / "summary.json") << R"({"finished": true, "normal_speed": [{"component": "gear", "p90_normal_speed_mps": 3.0}]})";
    const auto forecast = [&](double t) {
        if (too_short == "never") return std::string(R"({"status": "never"})");  // an area without an impact near it
        if (!too_short.empty()) return std::string(R"({"status": "too_short", "time_s": 100, "run_for_s": )") + too_short + "}";
        return R"({"status": "forecast", "time_s": )" + std::to_string(t) + R"(, "low_s": )" + std::to_string(0.95 * t) +
               R"(, "high_s": )" + std::to_string(1.08 * t) + "}";
    };
    std::ofstream(dir / "analysis" / "figures.json")
        << R"({"target_coverage": 0.9, "components": [{"component": "gear", "impact_rate_per_s": 1000, "mean_vn_mps": 2.0, "coverage": 0.1,)"
        << R"("share_below_target": )" << share_below << R"(, "time_to_target": )" << forecast(whole_s)
        << R"(, "time_to_target_everywhere": )" << forecast(everywhere_s) << R"(, "uniformity": {"value": )" << uniformity << R"(, "low": )"
        << uniformity - 0.02 << R"(, "high": )" << uniformity + 0.02 << R"(}, "regions": [)"
        << R"({"region": "tooth-0", "excluded": false, "impact_rate_per_s": 50, "coverage": 0.1, "time_to_target": )"
        << forecast(slow_tooth_s) << "},"
        << R"({"region": "tooth-1", "excluded": false, "impact_rate_per_s": 60, "coverage": 0.2, "time_to_target": )"
        << forecast(0.5 * slow_tooth_s) << "},"
        << R"({"region": "bore", "excluded": true, "impact_rate_per_s": 0, "coverage": null, "time_to_target": {"status": "none"}}]}]})";
}

TEST(SweepCompare, TheSlowestRegionEverywhereUniformityAndShareBelowEachWithAVerdict) {
    TempDir dir;
    SweepPlan plan =
        plan_sweep({parse_sweep_axis("components[gear].motion.speed=0 rpm,30 rpm,60 rpm,90 rpm")}, 2, 1, {}, (dir.path / "s").string());
    for (const SweepRun& run : plan.runs) {
        const double jitter = run.replicate == 0 ? 1.0 : 1.02;
        if (run.variant == 0) write_fake_run(run.dir, 450.0 * jitter, 1400.0 * jitter, 1500.0 * jitter, 0.35, 0.2 * jitter);
        if (run.variant == 1) write_fake_run(run.dir, 455.0 * jitter, 700.0 * jitter, 720.0 * jitter, 0.8, 0.1 * jitter);
        if (run.variant == 2) write_fake_run(run.dir, 0, 0, 0, 0.8, 0.1, run.replicate == 0 ? "600" : "900");
        if (run.variant == 3) write_fake_run(run.dir, 0, 0, 0, 0.8, 0.1, "never");
    }
    write_sweep_comparison(plan, (dir.path / "s" / "sweep").string(), "", "gear");
    const std::string csv = read_file(dir.path / "s" / "sweep" / "comparison.csv");
    const std::string header = csv.substr(0, csv.find('\n'));
    for (const char* column :
         {"slowest_region_time_to_target_s", "slowest_region_time_to_target_s_ci95", "time_to_target_everywhere_s", "uniformity_ci95",
          "share_below_target_ci95", "verdict_slowest_region_time_to_target_s", "verdict_time_to_target_everywhere_s", "verdict_uniformity",
          "verdict_share_below_target", "verdict_time_to_target_s", "region_tooth-0_time_to_target_s",
          "region_tooth-0_time_to_target_ci95_s", "slowest_region"})
        EXPECT_NE(header.find(std::string(",") + column), std::string::npos) << column << " in " << header;
    const std::string report = read_file(dir.path / "s" / "sweep" / "report.md");
    EXPECT_NE(report.find("## What decides: time to 90 %"), std::string::npos) << report;
    // The 30 rpm row: the whole part's time is within noise, the slowest tooth halves and differs.
    const auto row_of = [&](const std::string& text, const std::string& name) {
        const auto b = text.find("| " + name + " |");
        return b == std::string::npos ? std::string() : text.substr(b, text.find('\n', b) - b);
    };
    const std::string rotating = row_of(report, "speed-30rpm");
    EXPECT_NE(rotating.find("| tooth-0 | 707 +- "), std::string::npos) << rotating;
    EXPECT_NE(rotating.find("(differs) | 727.2 +- "), std::string::npos) << rotating;
    EXPECT_NE(rotating.find("(within noise) |"), std::string::npos) << rotating;           // the whole part: 459.5 vs 454.5
    EXPECT_EQ(rotating.find("within noise"), rotating.rfind("within noise")) << rotating;  // only there
    // A variant whose runs are too short says so and how long to run, instead of a number.
    EXPECT_NE(row_of(report, "speed-60rpm").find("too short: run 900 s"), std::string::npos) << report;
    // One with an area no impact came near: never, at the rate its runs measured (not "the part has
    // no impact": it has, 1000 per second).
    EXPECT_NE(row_of(report, "speed-90rpm").find("never at this rate: part of it has had no impact near it (a longer run may find one)"),
              std::string::npos)
        << report;
    // The one-seed interval is the run's own (its wider side).
    SweepPlan one = plan_sweep({parse_sweep_axis("components[gear].motion.speed=0 rpm")}, 1, 1, {}, (dir.path / "o").string());
    write_fake_run(one.runs[0].dir, 400.0, 1000.0, 1100.0, 0.5, 0.2);
    write_sweep_comparison(one, (dir.path / "o" / "sweep").string(), "", "gear");
    EXPECT_NE(read_file(dir.path / "o" / "sweep" / "report.md").find("| tooth-0 | 1000 +- 80 |"), std::string::npos)
        << read_file(dir.path / "o" / "sweep" / "report.md");
}

SweepOptions rod_sweep(const fs::path& dir, int jobs) {
    SweepOptions o;
    o.scene_path = kRod;
    o.output_dir = dir.string();
    o.vary = {"shot.count=64,128"};
    o.overrides = {"process.duration=20 ms"};
    o.jobs = jobs;
    o.executable = PEENSIM_BINARY;
    return o;
}

TEST(SweepJob, EachRunIsTheRunAloneWhateverTheJobsAndFinishedRunsAreKept) {
    TempDir dir;
    std::ostringstream out1, err1, out2, err2;
    ASSERT_EQ(sweep_job(rod_sweep(dir.path / "one", 1), out1, err1), kExitOk) << err1.str();
    ASSERT_EQ(sweep_job(rod_sweep(dir.path / "two", 2), out2, err2), kExitOk) << err2.str();
    EXPECT_NE(out2.str().find("sweep: 2 variants x 1 seed = 2 runs, 2 at once"), std::string::npos) << out2.str();
    // The same run alone, as `peensim run` does it.
    RunOptions alone;
    alone.scene_path = kRod;
    alone.output_dir = (dir.path / "alone").string();
    alone.overrides = {"process.duration=20 ms", "shot.count=128", "process.seed=1"};
    alone.progress = false;
    std::ostringstream o, e;
    ASSERT_EQ(run_job(alone, o, e), kExitOk) << e.str();
    const std::string log = read_file(dir.path / "alone" / "impacts.csv");
    EXPECT_GT(log.size(), 1000u);
    EXPECT_EQ(read_file(dir.path / "one" / "count-128" / "s0" / "impacts.csv"), log);
    EXPECT_EQ(read_file(dir.path / "two" / "count-128" / "s0" / "impacts.csv"), log);
    EXPECT_EQ(read_file(dir.path / "one" / "count-64" / "s0" / "impacts.csv"),
              read_file(dir.path / "two" / "count-64" / "s0" / "impacts.csv"));
    // One after the other, the second run read the rod's coverage geometry the first kept
    // (coverage_geometry_cache.h): its analysis is the one of the run alone, which computed it.
    EXPECT_NE(out1.str().find("geometry: the runs computed the parts' coverage geometry 1 time and reused it 1 time (" +
                              (dir.path / "one" / "sweep" / "geometry-cache").string() + ")"),
              std::string::npos)
        << out1.str();
    EXPECT_NE(read_file(dir.path / "one" / "sweep" / "logs" / "count-128.s0.log").find("note: rod's coverage geometry reused from "),
              std::string::npos);
    for (const char* table : {"rod_triangles.csv", "rod_coverage.csv", "figures.json"})
        EXPECT_EQ(read_file(dir.path / "one" / "count-128" / "s0" / "analysis" / table), read_file(dir.path / "alone" / "analysis" / table))
            << table;
    // The comparison: one row per variant, the run's own figures.
    const std::string csv = read_file(dir.path / "one" / "sweep" / "comparison.csv");
    EXPECT_EQ(csv.rfind("variant,shot.count,runs_finished,target_coverage,impact_rate_per_s,impact_rate_per_s_ci95,mean_vn_mps,", 0), 0u)
        << csv;
    EXPECT_NE(csv.find("\ncount-64,\"64\",1,"), std::string::npos) << csv;
    EXPECT_NE(csv.find("\ncount-128,\"128\",1,"), std::string::npos) << csv;
    const std::string report = read_file(dir.path / "one" / "sweep" / "report.md");
    EXPECT_NE(report.find("| count-128 | 1/1 |"), std::string::npos) << report;
    EXPECT_NE(report.find("baseline `count-64`"), std::string::npos) << report;
    // Run again: nothing is rerun (the logs keep their bytes and times), the comparison is rewritten.
    const auto written = fs::last_write_time(dir.path / "one" / "count-64" / "s0" / "impacts.csv");
    std::ostringstream out3, err3;
    ASSERT_EQ(sweep_job(rod_sweep(dir.path / "one", 1), out3, err3), kExitOk) << err3.str();
    EXPECT_NE(out3.str().find("2 finished before"), std::string::npos) << out3.str();
    EXPECT_EQ(fs::last_write_time(dir.path / "one" / "count-64" / "s0" / "impacts.csv"), written);
    // Run again with another value: the finished runs are not this sweep's, and are neither
    // skipped (their results compared as the variants') nor replaced; refused before any run.
    SweepOptions other = rod_sweep(dir.path / "one", 1);
    other.overrides.push_back("shot.diameter=1.5 mm");
    std::ostringstream out4, err4;
    EXPECT_EQ(sweep_job(other, out4, err4), kExitInputError) << out4.str();
    EXPECT_NE(
        err4.str().find("count-64/s0 finished with another scene (its text or a mesh file's bytes) or other values than this sweep "
                        "gives variant 'count-64' "
                        "(shot.count=64); what differs: shot: the run had `diameter: 0.002  # m`, now `diameter: 0.0015  # m`; so did " +
                        (dir.path / "one" / "count-128" / "s0").string() +
                        "; the sweep would skip them and compare their results as this variant's; write this sweep to another folder"),
        std::string::npos)
        << err4.str();
    EXPECT_EQ(fs::last_write_time(dir.path / "one" / "count-64" / "s0" / "impacts.csv"), written);
}

// Runs that would record an animation without a render module to draw it are refused before any
// run, as a STEP part without the CAD module is (each run would stop at its start, exit 1, and be
// retried once). In a child: this process may have loaded the module already.
// An interrupted run of another scene in a sweep's folders is refused before any run too: its resume
// would be refused after the other runs had run with the new scene beside it.
TEST(SweepJob, AnInterruptedRunOfAnotherSceneIsRefusedBeforeAnyRun) {
    TempDir dir;
    const fs::path stopped = dir.path / "count-64" / "s0";
    const ShellResult run = run_shell("'" + std::string(PEENSIM_BINARY) + "' run '" + kRod + "' -o '" + stopped.string() +
                                      "' -q --no-analyze --set process.duration=20ms --set shot.count=64 --set \"shot.diameter=1.5 mm\" "
                                      "--set accuracy.scheme=step --stop-after-steps 5 2>&1");
    ASSERT_EQ(WEXITSTATUS(run.status), 130) << run.output;
    ASSERT_TRUE(fs::exists(stopped / "checkpoint.bin"));
    std::ostringstream out, err;
    SweepOptions sweep = rod_sweep(dir.path, 1);
    sweep.overrides.push_back("accuracy.scheme=step");
    EXPECT_EQ(sweep_job(sweep, out, err), kExitInputError) << out.str();
    EXPECT_NE(err.str().find("count-64/s0 was interrupted (its checkpoint.bin) with another scene"), std::string::npos) << err.str();
    EXPECT_NE(err.str().find("what differs: shot: the run had `diameter: 0.0015  # m`, now `diameter: 0.002  # m`"), std::string::npos)
        << err.str();
    EXPECT_FALSE(fs::exists(dir.path / "count-128")) << out.str();  // no run started
}

TEST(SweepJob, AnAnimationWithoutTheRenderModuleIsRefusedBeforeAnyRun) {
    TempDir dir;
    const fs::path junk = dir.path / "junk.so";
    std::ofstream(junk) << "not a module\n";
    const ShellResult sweep =
        run_shell("PEENSIM_RENDER_MODULE='" + junk.string() + "' '" + PEENSIM_BINARY + "' sweep '" + kRod + "' -o '" +
                  (dir.path / "sweep").string() + "' --vary shot.count=32,64 --set process.duration=0.05 --set render.width=320 2>&1");
    EXPECT_EQ(WEXITSTATUS(sweep.status), 1) << sweep.output;
    EXPECT_NE(sweep.output.find("the runs record an animation (the scene's render block): rendering needs libpeensim_render.so"),
              std::string::npos)
        << sweep.output;
    EXPECT_FALSE(fs::exists(dir.path / "sweep")) << sweep.output;
    // A variant that adds the render block is named.
    const ShellResult variant =
        run_shell("PEENSIM_RENDER_MODULE='" + junk.string() + "' '" + PEENSIM_BINARY + "' sweep '" + kRod + "' -o '" +
                  (dir.path / "variant").string() + "' --vary render.width=320,640 --set process.duration=0.05 2>&1");
    EXPECT_EQ(WEXITSTATUS(variant.status), 1) << variant.output;
    EXPECT_NE(variant.output.find("variant 'width-320' records an animation (its render block)"), std::string::npos) << variant.output;
    // Without the render block, the same sweep does not need the module for its runs (their
    // reports say which pictures are missing): not refused.
    const ShellResult plain = run_shell("PEENSIM_RENDER_MODULE='" + junk.string() + "' '" + PEENSIM_BINARY + "' sweep '" + kRod + "' -o '" +
                                        (dir.path / "plain").string() + "' --vary shot.count=32,64 --set process.duration=0.02 2>&1");
    EXPECT_EQ(WEXITSTATUS(plain.status), 0) << plain.output;
}

TEST(SweepJob, AFailingRunIsRetriedOnceThenReportedAndBadInputsExitTwo) {
    TempDir dir;
    SweepOptions o = rod_sweep(dir.path / "fail", 2);
    o.executable = "/bin/false";  // every run fails
    std::ostringstream out, err;
    EXPECT_EQ(sweep_job(o, out, err), kExitRuntimeError);
    EXPECT_NE(err.str().find("count-64/s0 failed (exit 1"), std::string::npos) << err.str();
    EXPECT_NE(err.str().find("trying it once more"), std::string::npos) << err.str();
    EXPECT_NE(err.str().find("count-64/s0 failed again"), std::string::npos) << err.str();
    EXPECT_NE(read_file(dir.path / "fail" / "sweep" / "report.md").find("| count-64 | 0/1 |"), std::string::npos);
    // A bad value is refused before anything runs: exit 2, naming the field.
    SweepOptions bad = rod_sweep(dir.path / "bad", 1);
    bad.vary = {"shot.count=64,-5"};
    std::ostringstream out2, err2;
    EXPECT_EQ(sweep_job(bad, out2, err2), kExitInputError);
    EXPECT_NE(err2.str().find("shot.count"), std::string::npos) << err2.str();
    EXPECT_FALSE(fs::exists(dir.path / "bad" / "count-64"));
    SweepOptions unknown = rod_sweep(dir.path / "unknown", 1);
    unknown.vary = {"shot.colour=red,blue"};
    std::ostringstream out3, err3;
    EXPECT_EQ(sweep_job(unknown, out3, err3), kExitInputError);
    EXPECT_NE(err3.str().find("colour"), std::string::npos) << err3.str();
}

// A run that refuses its input (exit 2: a mesh this installation cannot read, a directory in use) is
// not run again: the same run would be refused for the same reason.
TEST(SweepJob, ARunThatRefusesItsInputIsNotRunAgain) {
    TempDir dir;
    const fs::path refusing = dir.path / "refusing.sh";
    {
        std::ofstream script(refusing);
        script << "#!/bin/sh\necho \"error: rod.step: mesh: reading STEP/IGES needs libpeensim_cad.so\" >&2\nexit 2\n";
    }
    fs::permissions(refusing, fs::perms::owner_all);
    SweepOptions o = rod_sweep(dir.path / "refused", 1);
    o.executable = refusing.string();
    // A variant's folder that is a link of the user's: left as it is, as is what it points to.
    fs::create_directories(dir.path / "elsewhere");
    std::ofstream(dir.path / "elsewhere" / "notes.txt") << "precious\n";
    fs::create_directories(dir.path / "refused");
    fs::create_directory_symlink(dir.path / "elsewhere", dir.path / "refused" / "count-64");
    std::ostringstream out, err;
    EXPECT_EQ(sweep_job(o, out, err), kExitRuntimeError);
    EXPECT_NE(err.str().find("count-64/s0 refused its input (exit 2"), std::string::npos) << err.str();
    EXPECT_NE(err.str().find("count-128/s0 refused its input (exit 2"), std::string::npos) << err.str();
    EXPECT_EQ(err.str().find("trying it once more"), std::string::npos) << err.str();
    const std::string log = read_file(dir.path / "refused" / "sweep" / "logs" / "count-64.s0.log");
    EXPECT_EQ(log.find("error: rod.step"), log.rfind("error: rod.step")) << log;  // run once
    EXPECT_NE(read_file(dir.path / "refused" / "sweep" / "report.md").find("| count-64 | 0/1 |"), std::string::npos);
    // The end says how many failed and where why is; the runs wrote nothing, and left no folder.
    EXPECT_NE(err.str().find("sweep: 2 of 2 runs failed for good (why: their logs in " +
                             (dir.path / "refused" / "sweep" / "logs").string() + "); the comparison leaves them out"),
              std::string::npos)
        << err.str();
    EXPECT_FALSE(fs::exists(dir.path / "refused" / "count-128")) << err.str();
    EXPECT_TRUE(fs::is_symlink(dir.path / "refused" / "count-64")) << err.str();
    EXPECT_EQ(read_file(dir.path / "elsewhere" / "notes.txt"), "precious\n");
}

// Ctrl-C stops a sweep with its runs checkpointed (exit 130); the same command goes on, and every
// run's log is then the uninterrupted sweep's, byte for byte.
TEST(SweepJob, AnInterruptedSweepGoesOnWhereItStopped) {
    TempDir dir;
    const auto args = [&](const fs::path& out) {
        return std::vector<std::string>{PEENSIM_BINARY,
                                        "sweep",
                                        kRod,
                                        "-o",
                                        out.string(),
                                        "--vary",
                                        "shot.count=256,512",
                                        "--set",
                                        "process.duration=6 s",
                                        "--set",
                                        "output.checkpoint_interval=0.2 s",
                                        "--jobs",
                                        "2"};
    };
    ChildProcess whole(args(dir.path / "whole"), (dir.path / "whole.out").string(), (dir.path / "whole.err").string());
    ASSERT_EQ(whole.wait_exit(300.0), std::optional<int>(kExitOk)) << read_file(dir.path / "whole.err");
    ChildProcess stopped(args(dir.path / "parts"), (dir.path / "parts.out").string(), (dir.path / "parts.err").string());
    // Once the longer run has written a checkpoint it is well under way.
    for (int k = 0; k < 3000 && !fs::exists(dir.path / "parts" / "count-512" / "s0" / "checkpoint.bin"); ++k)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    stopped.signal(SIGINT);
    ASSERT_EQ(stopped.wait_exit(120.0), std::optional<int>(kExitInterrupted)) << read_file(dir.path / "parts.err");
    EXPECT_NE(read_file(dir.path / "parts.err").find("sweep: interrupted"), std::string::npos) << read_file(dir.path / "parts.err");
    EXPECT_FALSE(fs::exists(dir.path / "parts" / "count-512" / "s0" / "impacts.csv"));  // not finished: its log is partial
    ChildProcess resumed(args(dir.path / "parts"), (dir.path / "resumed.out").string(), (dir.path / "resumed.err").string());
    ASSERT_EQ(resumed.wait_exit(300.0), std::optional<int>(kExitOk)) << read_file(dir.path / "resumed.err");
    for (const char* run : {"count-256/s0", "count-512/s0"})
        EXPECT_EQ(read_file(dir.path / "parts" / run / "impacts.csv"), read_file(dir.path / "whole" / run / "impacts.csv")) << run;
}

// `mpirun -n 2 peensim sweep ...`: rank 0 hands the runs out, both ranks run them, and each run's
// log is the one a local sweep (and the run alone) writes.
TEST(SweepMpi, RanksShareTheRunsAndEachRunIsTheLocalOne) {
    const std::string mpirun = "/usr/bin/mpirun";
    ASSERT_TRUE(fs::exists(mpirun)) << "mpirun not found: .ci/install-deps installs openmpi-bin";
    TempDir dir;
    std::ostringstream out, err;
    ASSERT_EQ(sweep_job(rod_sweep(dir.path / "local", 1), out, err), kExitOk) << err.str();
    mpirun_environment();
    ChildProcess mpi({mpirun, "-n", "2", "--oversubscribe", PEENSIM_BINARY, "sweep", kRod, "-o", (dir.path / "mpi").string(), "--vary",
                      "shot.count=64,128", "--set", "process.duration=20 ms"},
                     (dir.path / "mpi.out").string(), (dir.path / "mpi.err").string());
    ASSERT_EQ(mpi.wait_exit(300.0), std::optional<int>(kExitOk)) << read_file(dir.path / "mpi.err") << read_file(dir.path / "mpi.out");
    const std::string said = read_file(dir.path / "mpi.out");
    EXPECT_NE(said.find("sweep: 2 variants x 1 seed = 2 runs over 2 MPI ranks"), std::string::npos) << said;
    EXPECT_NE(said.find("comparison: "), std::string::npos) << said;  // rank 0's, once
    EXPECT_EQ(said.find("comparison: "), said.rfind("comparison: ")) << said;
    for (const char* run : {"count-64/s0", "count-128/s0"})
        EXPECT_EQ(read_file(dir.path / "mpi" / run / "impacts.csv"), read_file(dir.path / "local" / run / "impacts.csv")) << run;
    EXPECT_NE(read_file(dir.path / "mpi" / "sweep" / "report.md").find("| count-128 | 1/1 |"), std::string::npos);
    // The two ranks' runs share the rod's coverage geometry in the sweep's folder: one computes
    // it, the other waits and reads it.
    EXPECT_NE(said.find("geometry: the runs computed the parts' coverage geometry 1 time and reused it 1 time"), std::string::npos) << said;
}

// A sweep file: the variants listed by name, the seeds, the set and the baseline from the file.
TEST(SweepJob, ASweepFileListsNamedVariants) {
    TempDir dir;
    const fs::path file = dir.path / "study.yaml";
    std::ofstream(file) << "scene: " << kRod << "\n"
                        << "seeds: 2\n"
                        << "set: [\"process.duration=10 ms\"]\n"
                        << "variants:\n"
                        << "  - {name: few, set: {shot.count: 64}}\n"
                        << "  - {name: many, set: {shot.count: 128, process.gravity: [0, 0, -9.81]}}\n"
                        << "baseline: many\n";
    SweepOptions o;
    o.scene_path = file.string();
    o.output_dir = (dir.path / "out").string();
    o.jobs = 2;
    o.executable = PEENSIM_BINARY;
    std::ostringstream out, err;
    ASSERT_EQ(sweep_job(o, out, err), kExitOk) << err.str();
    EXPECT_NE(out.str().find("2 variants x 2 seeds = 4 runs"), std::string::npos) << out.str();
    for (const char* run : {"few/s0", "few/s1", "many/s0", "many/s1"})
        EXPECT_TRUE(fs::exists(dir.path / "out" / run / "impacts.csv")) << run;
    // The seeds differ (process.seed 1 and 2): two runs of one variant are not the same run.
    EXPECT_NE(read_file(dir.path / "out" / "few" / "s0" / "impacts.csv"), read_file(dir.path / "out" / "few" / "s1" / "impacts.csv"));
    const std::string report = read_file(dir.path / "out" / "sweep" / "report.md");
    EXPECT_NE(report.find("baseline `many`"), std::string::npos) << report;
    EXPECT_NE(report.find("| few | 2/2 |"), std::string::npos) << report;
    EXPECT_NE(report.find("Student's t over the seed replicates"), std::string::npos) << report;
    // Every figure of the runs comes from the runs: the p90 speed from their summaries (none is missing).
    EXPECT_EQ(report.substr(report.find("## The runs' figures")).find("| - |"), std::string::npos) << report;
    const std::string csv = read_file(dir.path / "out" / "sweep" / "comparison.csv");
    EXPECT_EQ(csv.rfind("variant,shot.count,process.gravity,runs_finished,", 0), 0u) << csv;
    // A file's mistakes point at its line: an unknown key, a bad baseline.
    std::ofstream(file) << "scene: " << kRod << "\nseed: 3\n";
    std::ostringstream out2, err2;
    EXPECT_EQ(sweep_job(o, out2, err2), kExitInputError);
    EXPECT_NE(err2.str().find("study.yaml:2:1: seed: unknown key in a sweep file"), std::string::npos) << err2.str();
    std::ofstream(file) << "scene: " << kRod << "\nvary: {shot.count: [64]}\nbaseline: nothing\n";
    std::ostringstream out3, err3;
    EXPECT_EQ(sweep_job(o, out3, err3), kExitInputError);
    EXPECT_NE(err3.str().find("no variant is named 'nothing'"), std::string::npos) << err3.str();
}

}  // namespace
}  // namespace peensim::testing
