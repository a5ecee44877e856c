// `peensim analyze` end to end on short rod runs: its per-triangle counts add up to the impact
// log, coverage only grows, and an interrupted run, a run without a part and a directory that is
// not a run get clear messages, never a crash.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "analysis/impact_log_reader.h"
#include "app/analysis/analyze_job.h"
#include "app/analysis/coverage_geometry.h"
#include "app/run/run_job.h"
#include "model/model.h"
#include "output/atomic_file.h"
#include "scene/scene_parser.h"
#include "support/csv_columns.h"
#include "support/files.h"
#include "support/shell_command.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using peensim::testing::TempDir;
using namespace peensim;

namespace {

RunOptions rod_run(const fs::path& dir, double duration) {
    RunOptions o;
    o.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml";
    o.output_dir = dir.string();
    o.overrides = {"process.duration=" + std::to_string(duration)};
    o.progress = false;
    o.analyze = false;
    return o;
}

}  // namespace

TEST(AnalyzeJob, CountsAddUpAndCoverageOnlyGrows) {
    TempDir dir;
    std::ostringstream out, err;
    ASSERT_EQ(run_job(rod_run(dir.path, 0.1), out, err), kExitOk) << err.str();
    ASSERT_EQ(analyze_job(dir.path.string(), out, err), kExitOk) << err.str();
    std::uint64_t rows = 0;
    {
        ImpactLogReader reader((dir.path / "impacts.csv").string());
        ImpactRow row;
        while (reader.next(row)) ++rows;
    }
    ASSERT_GT(rows, 50u);
    const fs::path a = dir.path / "analysis";
    EXPECT_EQ(peensim::testing::csv_column_sum(a / "rod_triangles.csv", "impacts"), static_cast<double>(rows));
    EXPECT_EQ(peensim::testing::csv_column_sum(a / "rod_histograms.csv", "count"), 3.0 * static_cast<double>(rows));  // three histograms
    std::ifstream curve(a / "rod_coverage.csv");
    std::string line;
    std::getline(curve, line);
    double last = -1.0, t = 0.0, c = 0.0;
    int points = 0;
    char comma;
    while (curve >> t >> comma >> c) {
        EXPECT_GE(c, last);
        last = c;
        ++points;
    }
    EXPECT_EQ(points, 51);
    EXPECT_GT(last, 0.0);
    std::ifstream report(a / "report.md");
    const std::string text((std::istreambuf_iterator<char>(report)), {});
    EXPECT_NE(text.find("| rod | " + std::to_string(rows) + " |"), std::string::npos) << text;
    // The ParaView files (their format is checked against VTK's reader in output/vtp_test.cpp).
    EXPECT_GT(fs::file_size(a / "rod.vtp"), 6720u * 6 * 8);  // six cell fields of doubles at least
    EXPECT_GT(fs::file_size(a / "rod_impacts.vtp"), rows * 8 * 8);
}

// figures.json: the report's figures as data, agreeing with the log they come from.
// analysis/ holds one analysis: a file an earlier one wrote (a picture under an old name) is gone
// after the next, and neither the page nor the folder mention it; the analysis is written beside
// and replaces the folder whole, so nothing half written is left either.
TEST(AnalyzeJob, AnotherAnalysisReplacesTheFolderWholeLeavingNothingOfTheEarlierOne) {
    TempDir dir;
    std::ostringstream out, err;
    ASSERT_EQ(run_job(rod_run(dir.path, 0.1), out, err), kExitOk) << err.str();
    ASSERT_EQ(analyze_job(dir.path.string(), out, err), kExitOk) << err.str();
    const fs::path a = dir.path / "analysis";
    write_file_atomically((a / "rod_least_covered.png").string(), "an earlier analysis's picture");
    ASSERT_EQ(analyze_job(dir.path.string(), out, err), kExitOk) << err.str();
    EXPECT_FALSE(fs::exists(a / "rod_least_covered.png"));
    EXPECT_TRUE(fs::exists(a / "report.md"));
    EXPECT_TRUE(fs::exists(a / "figures.json"));
    EXPECT_FALSE(fs::exists(dir.path / "analysis.partial"));
    EXPECT_EQ(read_file(a / "report.html").find("least_covered"), std::string::npos);
    // The ParaView script points at the folder, not at where it was written.
    const std::string script = read_file(a / "open_in_paraview.py");
    EXPECT_NE(script.find(fs::absolute(a).string()), std::string::npos);
    EXPECT_EQ(script.find("analysis.partial"), std::string::npos);
}

TEST(AnalyzeJob, FiguresJsonAgreesWithTheLog) {
    TempDir dir;
    std::ostringstream out, err;
    ASSERT_EQ(run_job(rod_run(dir.path, 0.1), out, err), kExitOk) << err.str();
    ASSERT_EQ(analyze_job(dir.path.string(), out, err), kExitOk) << err.str();
    std::uint64_t rows = 0;
    double speed = 0.0;
    std::vector<std::uint64_t> batch(10, 0);
    {
        ImpactLogReader reader((dir.path / "impacts.csv").string());
        for (ImpactRow row; reader.next(row);) {
            ++rows;
            speed += row.vn_in_m_per_s;
            ++batch[static_cast<std::size_t>(std::min(9, static_cast<int>(row.time_s / 0.1 * 10)))];
        }
    }
    std::ifstream in(dir.path / "analysis" / "figures.json");
    const auto j = nlohmann::json::parse(in);
    EXPECT_DOUBLE_EQ(j["duration_s"].get<double>(), 0.1);
    const auto& rod = j["components"][0];
    EXPECT_EQ(rod["component"], "rod");
    EXPECT_EQ(rod["impacts"].get<std::uint64_t>(), rows);
    EXPECT_NEAR(rod["impact_rate_per_s"].get<double>(), static_cast<double>(rows) / 0.1, 1e-9);
    EXPECT_NEAR(rod["mean_vn_mps"].get<double>(), speed / static_cast<double>(rows), 1e-12);
    for (std::size_t b = 0; b < 10; ++b)
        EXPECT_NEAR(rod["batch_impact_rate_per_s"][b].get<double>(), static_cast<double>(batch[b]) / 0.01, 1e-6) << "batch " << b;
    EXPECT_GT(rod["coverage"].get<double>(), 0.0);
    EXPECT_GT(rod["time_to_target"]["time_s"].get<double>(), 0.0);
    EXPECT_TRUE(rod["time_to_target"]["high_s"].is_number());
    EXPECT_TRUE(rod["regions"].is_array());
}

TEST(AnalyzeJob, AnInterruptedRunIsAnalysedWithANote) {
    TempDir dir;
    std::ostringstream out, err;
    RunOptions o = rod_run(dir.path, 0.2);
    o.overrides.push_back("accuracy.scheme=step");  // stopped after a count of time steps
    o.stop_after_steps = 2000;
    ASSERT_EQ(run_job(o, out, err), kExitInterrupted) << err.str();
    // Cut the partial log mid-row, as a crash would.
    const fs::path partial = dir.path / "impacts.csv.partial";
    fs::resize_file(partial, fs::file_size(partial) - 5);
    std::ostringstream out2, err2;
    EXPECT_EQ(analyze_job(dir.path.string(), out2, err2), kExitOk) << err2.str();
    EXPECT_NE(err2.str().find("did not finish"), std::string::npos) << err2.str();
    std::ifstream report(dir.path / "analysis" / "report.md");
    const std::string text((std::istreambuf_iterator<char>(report)), {});
    EXPECT_NE(text.find("partial"), std::string::npos);
    EXPECT_NE(text.find("left out"), std::string::npos);
}

// A run hands its own model to its analysis (the meshes are not loaded, nor the BVHs built, twice),
// and the coverage geometry it computed on a thread of its own while it stepped:
// the tables are byte for byte those a later `peensim analyze` writes from the directory alone,
// and a model of another scene is never taken for the directory's.
TEST(AnalyzeJob, ARunsOwnAnalysisEqualsALaterOneAndNoOtherModelIsUsed) {
    TempDir dir;
    std::ostringstream out, err;
    RunOptions o = rod_run(dir.path, 0.1);
    o.analyze = true;
    ASSERT_EQ(run_job(o, out, err), kExitOk) << err.str();
    const fs::path a = dir.path / "analysis";
    const std::vector<std::string> tables = {"rod_triangles.csv", "rod_coverage.csv", "rod_histograms.csv", "figures.json"};
    std::map<std::string, std::string> by_run;
    for (const std::string& t : tables) by_run[t] = peensim::testing::read_file(a / t);
    ASSERT_GT(by_run["rod_triangles.csv"].size(), 1000u);
    const auto expect_tables_as_by_run = [&](const std::string& how) {
        for (const std::string& t : tables) EXPECT_EQ(peensim::testing::read_file(a / t), by_run[t]) << how << ": " << t;
    };
    ASSERT_EQ(analyze_job(dir.path.string(), out, err), kExitOk) << err.str();
    expect_tables_as_by_run("a later analyze");
    AnalyzeOptions other;
    other.model = compile_model(parse_scene_file(std::string(PEENSIM_SOURCE_DIR) + "/scenes/gear.yaml"));
    other.geometry = std::make_shared<CoverageGeometry>(other.model, nullptr, 0);
    ASSERT_EQ(analyze_job(dir.path.string(), out, err, other), kExitOk) << err.str();
    expect_tables_as_by_run("given the gear's model and its coverage geometry");
}

TEST(AnalyzeJob, NoPartAndNotARunAreClearErrors) {
    TempDir dir;
    std::ostringstream out, err;
    RunOptions o = rod_run(dir.path, 0.01);
    o.overrides.push_back("components[rod].role=fixture");
    o.overrides.push_back("output.log=[]");
    ASSERT_EQ(run_job(o, out, err), kExitOk) << err.str();
    std::ostringstream err2;
    EXPECT_EQ(analyze_job(dir.path.string(), out, err2), kExitRuntimeError);
    EXPECT_NE(err2.str().find("logged no component"), std::string::npos) << err2.str();
    std::ostringstream err3;
    EXPECT_EQ(analyze_job((dir.path / "nothing").string(), out, err3), kExitRuntimeError);
    EXPECT_NE(err3.str().find("not a peensim run directory"), std::string::npos) << err3.str();
}

namespace {

// Rows of <c>_histograms.csv: (region, quantity) -> total count.
std::map<std::pair<std::string, std::string>, std::uint64_t> histogram_totals(const fs::path& path) {
    std::map<std::pair<std::string, std::string>, std::uint64_t> totals;
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "region,quantity,bin_low,bin_high,unit,count");
    while (std::getline(in, line)) {
        std::stringstream ls(line);
        std::string region, quantity;
        std::getline(ls, region, ',');
        std::getline(ls, quantity, ',');
        totals[{region, quantity}] += std::stoull(line.substr(line.rfind(',') + 1));
    }
    return totals;
}

}  // namespace

TEST(AnalyzeJob, GearTeethHistogramsAddUpToTheWholeGear) {
    TempDir dir;
    RunOptions o = rod_run(dir.path, 0.3);
    o.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/gear.yaml";
    std::ostringstream out, err;
    ASSERT_EQ(run_job(o, out, err), kExitOk) << err.str();
    ASSERT_EQ(analyze_job(dir.path.string(), out, err), kExitOk) << err.str();
    const auto totals = histogram_totals(dir.path / "analysis" / "gear_histograms.csv");
    // The 20 tooth sectors tile the gear: every impact lands in exactly one tooth's histograms.
    for (const std::string quantity : {"normal_speed", "impact_angle", "dent_diameter"}) {
        std::uint64_t teeth = 0;
        int regions = 0;
        for (const auto& [key, count] : totals)
            if (key.second == quantity && key.first != "all") teeth += count, ++regions;
        EXPECT_GT(totals.at({"all", quantity}), 0u) << quantity;
        EXPECT_EQ(teeth, totals.at({"all", quantity})) << quantity;
        EXPECT_LE(regions, 20) << quantity;
    }
    EXPECT_TRUE(fs::exists(dir.path / "analysis" / "gear_regions.csv"));
}

TEST(AnalyzeJob, AlmenStripReportsDoseAndNeedsCalibration) {
    TempDir dir;
    RunOptions o = rod_run(dir.path, 0.3);
    o.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/almen.yaml";
    std::ostringstream out, err;
    ASSERT_EQ(run_job(o, out, err), kExitOk) << err.str();
    ASSERT_EQ(analyze_job(dir.path.string(), out, err), kExitOk) << err.str();
    const fs::path csv = dir.path / "analysis" / "almen_almen.csv";
    ASSERT_TRUE(fs::exists(csv));
    // Dose never decreases; the arc-height column is empty without calibration.
    std::ifstream in(csv);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "time_s,dose_J_per_m2,arc_height_mm,dent_area_ratio,predicted_arc_height_mm");
    double last = -1.0;
    int rows = 0;
    while (std::getline(in, line)) {
        const double dose = std::stod(line.substr(line.find(',') + 1));
        EXPECT_GE(dose, last);
        EXPECT_EQ(line.back(), ',');
        last = dose;
        ++rows;
    }
    EXPECT_EQ(rows, 51);
    EXPECT_GT(last, 0.0);
    std::ifstream report(dir.path / "analysis" / "report.md");
    const std::string text((std::istreambuf_iterator<char>(report)), {});
    EXPECT_NE(text.find("Arc height needs calibration"), std::string::npos);
    EXPECT_NE(text.find("Not calibrated in this scene"), std::string::npos);

    // Calibrated through --set: arc heights appear, with the J443 saturation time.
    TempDir dir2;
    o.output_dir = dir2.path.string();
    o.overrides.push_back("components[almen].almen.saturation_arc_height=0.3 mm");
    o.overrides.push_back("components[almen].almen.dose_constant=500 J/m2");
    ASSERT_EQ(run_job(o, out, err), kExitOk) << err.str();
    ASSERT_EQ(analyze_job(dir2.path.string(), out, err), kExitOk) << err.str();
    std::ifstream report2(dir2.path / "analysis" / "report.md");
    const std::string text2((std::istreambuf_iterator<char>(report2)), {});
    EXPECT_NE(text2.find("Calibration: a = 0.3 mm, E_c = 500 J/m2"), std::string::npos) << text2;
    EXPECT_NE(text2.find("saturation time T = "), std::string::npos);
    EXPECT_NE(text2.find("intensity 0.27 mm"), std::string::npos);
    std::ifstream csv2(dir2.path / "analysis" / "almen_almen.csv");
    std::getline(csv2, line);
    std::getline(csv2, line);
    EXPECT_EQ(line, "0,0,0,0,");  // the strip's yield stress gives dents; no predictive calibration
}

// The report's pictures come from the render module: a peensim without it (a copy of the binary
// alone, its module path pointing nowhere) still analyses the run, its report saying why the
// picture of the rod's area out of reach is missing, and exits 0.
TEST(AnalyzeJob, WithoutTheRenderModuleTheReportSaysWhyAPictureIsMissing) {
    TempDir dir;
    fs::create_directories(dir.path / "bin" / "alone");
    const fs::path binary = dir.path / "bin" / "alone" / "peensim";
    fs::copy_file(PEENSIM_BINARY, binary);
    const fs::path out = dir.path / "out";
    const peensim::testing::ShellResult run = peensim::testing::run_shell(
        "PEENSIM_RENDER_MODULE='" + (dir.path / "nowhere.so").string() + "' '" + binary.string() + "' run '" + PEENSIM_SOURCE_DIR +
        "/scenes/rod.yaml' -o '" + out.string() + "' -q --no-render --set process.duration=0.05 2>&1");
    ASSERT_EQ(run.status, 0) << run.output;
    const std::string report = peensim::testing::read_file(out / "analysis" / "report.md");
    EXPECT_NE(report.find("Pictures: no picture of the area out of reach: rendering needs libpeensim_render.so"), std::string::npos)
        << report;
    EXPECT_FALSE(fs::exists(out / "analysis" / "rod_out_of_reach.png"));
    EXPECT_TRUE(fs::exists(out / "analysis" / "figures.json"));
    // Said on the console too (even to a quiet run), not only in the report.
    EXPECT_NE(run.output.find("warning: no picture of the area out of reach: rendering needs libpeensim_render.so"), std::string::npos)
        << run.output;
    // A module path that is set is the only one tried: a wrong one, with the right module beside
    // the binary, is said so (before, the one beside was drawn with, without a word).
    const fs::path junk = dir.path / "junk.so";
    std::ofstream(junk) << "not a module\n";
    const peensim::testing::ShellResult wrong = peensim::testing::run_shell(
        "PEENSIM_RENDER_MODULE='" + junk.string() + "' '" + PEENSIM_BINARY + "' run '" + PEENSIM_SOURCE_DIR + "/scenes/rod.yaml' -o '" +
        (dir.path / "wrong").string() + "' -q --no-render --set process.duration=0.05 2>&1");
    ASSERT_EQ(wrong.status, 0) << wrong.output;
    EXPECT_NE(wrong.output.find("which PEENSIM_RENDER_MODULE does not name:\n  " + junk.string()), std::string::npos) << wrong.output;
    EXPECT_FALSE(fs::exists(dir.path / "wrong" / "analysis" / "rod_out_of_reach.png"));
    // An animation asked for without a module to draw it: refused before the run writes anything.
    const peensim::testing::ShellResult animated = peensim::testing::run_shell(
        "PEENSIM_RENDER_MODULE='" + junk.string() + "' '" + PEENSIM_BINARY + "' run '" + PEENSIM_SOURCE_DIR + "/scenes/rod.yaml' -o '" +
        (dir.path / "animated").string() + "' -q --render --set process.duration=0.05 2>&1");
    EXPECT_EQ(WEXITSTATUS(animated.status), 1) << animated.output;
    EXPECT_NE(animated.output.find("rendering needs libpeensim_render.so"), std::string::npos) << animated.output;
    EXPECT_EQ(animated.output.find("--resume"), std::string::npos) << animated.output;  // nothing to resume
    EXPECT_FALSE(fs::exists(dir.path / "animated")) << animated.output;
}
