// `peensim almen-fit`: a measured curve in, the fits, intensity in mm, in and thou with the strip
// letter, J443's warnings, JSON; bad files refused (exit 2); and the predictive model's calibration
// round trip through real runs of scenes/almen.yaml: calibrate on a run, predict that run (the
// measured curve back), predict a run at another amplitude (the dent-size ratio).
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/almen/almen_fit_job.h"
#include "app/run/run_job.h"
#include "support/files.h"
#include "support/temp_dir.h"

namespace peensim {
namespace {

namespace fs = std::filesystem;
using peensim::testing::read_file;
using peensim::testing::TempDir;

std::string write(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
}

std::string exact(double v) {
    char b[32];
    const auto r = std::to_chars(b, b + sizeof(b), v);
    return std::string(b, r.ptr);
}

// A 2P curve, exact: a = 0.3 mm (0.011811 in), b = 0.5 /min; T = ln 10 / 0.5 = 4.605 min.
std::string exact_curve_csv(const std::vector<double>& minutes) {
    std::string s = "# synthetic: a = 0.3 mm, b = 0.5 /min\ntime_min,arc_height_in\n";
    for (double t : minutes) s += exact(t) + "," + exact(0.3 / 25.4 * -std::expm1(-0.5 * t)) + "\n";
    return s;
}

TEST(AlmenFitJob, FitsAMeasuredCurveAndWritesItsFigures) {
    TempDir dir;
    AlmenFitOptions o;
    o.curve_path = write(dir.path / "curve.csv", exact_curve_csv({1, 2, 3, 4, 6, 8, 12, 16}));
    o.strip = "A";
    o.json_path = (dir.path / "fit.json").string();
    std::ostringstream out, err;
    ASSERT_EQ(almen_fit_job(o, out, err), kExitOk) << err.str();
    EXPECT_EQ(err.str(), "");  // 8 strips bracketing T and 2T: no warning
    EXPECT_NE(out.str().find("Use the 2P fit: the 2P form already fits every strip to rounding"), std::string::npos) << out.str();
    // 0.9 x 0.3 mm = 0.27 mm = 0.01063 in = 10.63 thou.
    EXPECT_NE(out.str().find("Intensity 0.27 mm = 0.01063 in = 10.63 thou (0.0106A), saturation time T = 4.605 min (276.3 s)"),
              std::string::npos)
        << out.str();
    const nlohmann::json j = nlohmann::json::parse(read_file(o.json_path));
    EXPECT_EQ(j["used"], "2P");
    EXPECT_NEAR(j["intensity_m"].get<double>(), 0.27e-3, 1e-15);
    EXPECT_NEAR(j["intensity_thou"].get<double>(), 0.27 / 25.4 * 1e3, 1e-9);
    EXPECT_NEAR(j["saturation_time"].get<double>(), std::log(10.0) / 0.5, 1e-9);
    EXPECT_NEAR(j["saturation_time_s"].get<double>(), 60.0 * std::log(10.0) / 0.5, 1e-7);
    EXPECT_EQ(j["intensity_label"], "0.0106A");
    EXPECT_EQ(j["exposure_unit"], "min");
    EXPECT_EQ(j["height_unit"], "in");
    EXPECT_EQ(j["fits"].size(), 2u);
    EXPECT_EQ(j["fits"][1]["form"], "3P");
    EXPECT_NEAR(j["fits"][1]["c"].get<double>(), 1.0, 1e-6);
    EXPECT_TRUE(j["warnings"].empty());
}

// No output writes over the curve: `--plot X.png` next to X.csv keeps X.csv (its points go to
// X_points.csv), and an output that is the curve itself is refused before anything is written.
TEST(AlmenFitJob, NoOutputWritesOverTheCurve) {
    TempDir dir;
    const std::string text = exact_curve_csv({1, 2, 3, 4, 6, 8, 12, 16});
    AlmenFitOptions o;
    o.curve_path = write(dir.path / "curve.csv", text);
    o.plot_path = (dir.path / "curve.png").string();
    std::ostringstream out, err;
    ASSERT_EQ(almen_fit_job(o, out, err), kExitOk) << err.str();
    EXPECT_EQ(read_file(dir.path / "curve.csv"), text);
    if (fs::exists(dir.path / "curve.png")) {
        EXPECT_TRUE(fs::exists(dir.path / "curve_points.csv"));  // gnuplot present
    }
    AlmenFitOptions clash = o;
    clash.curve_path = write(dir.path / "c_points.csv", text);
    clash.plot_path = (dir.path / "c.png").string();
    std::ostringstream out2, err2;
    EXPECT_EQ(almen_fit_job(clash, out2, err2), kExitInputError);
    EXPECT_NE(err2.str().find("--plot"), std::string::npos) << err2.str();
    EXPECT_NE(err2.str().find("the curve being read"), std::string::npos) << err2.str();
    EXPECT_FALSE(fs::exists(dir.path / "c.gp"));
    AlmenFitOptions json = o;
    json.plot_path.clear();
    json.json_path = o.curve_path;
    std::ostringstream out3, err3;
    EXPECT_EQ(almen_fit_job(json, out3, err3), kExitInputError);
    EXPECT_NE(err3.str().find("--json"), std::string::npos) << err3.str();
    EXPECT_EQ(read_file(dir.path / "curve.csv"), text);
}

TEST(AlmenFitJob, WarnsWhereTheDataMissJ443sConditions) {
    TempDir dir;
    AlmenFitOptions o;
    o.curve_path = write(dir.path / "short.csv", exact_curve_csv({1, 2, 5}));  // T = 4.6 min: 2T = 9.2 beyond the last strip
    o.json_path = (dir.path / "fit.json").string();
    std::ostringstream out, err;
    ASSERT_EQ(almen_fit_job(o, out, err), kExitOk) << err.str();
    EXPECT_NE(err.str().find("only 3 distinct exposures: SAE J443 asks for a saturation curve of at least four strips"), std::string::npos)
        << err.str();
    EXPECT_NE(err.str().find("no strip was peened for 2T = 9.21 min or longer"), std::string::npos) << err.str();
    EXPECT_EQ(err.str().find("outside the measured exposures"), std::string::npos);  // T = 4.6 lies within 1..5
    EXPECT_EQ(nlohmann::json::parse(read_file(o.json_path))["warnings"].size(), 2u);
    // Without the strip letter the intensity has no label.
    EXPECT_EQ(out.str().find("A)"), std::string::npos);
}

TEST(AlmenFitJob, BadFilesAndCurvesWithoutSaturationExitTwo) {
    TempDir dir;
    AlmenFitOptions o;
    std::ostringstream out, err;
    o.curve_path = write(dir.path / "bad.csv", "time_min,arc_height_in\n1,0.006\n2,0.O09\n");
    EXPECT_EQ(almen_fit_job(o, out, err), kExitInputError);
    EXPECT_NE(err.str().find("bad.csv:3:3: arc_height_in: expected a number (the arc height in in), got '0.O09'"), std::string::npos)
        << err.str();
    err.str("");
    o.curve_path = write(dir.path / "line.csv", "time_s,arc_height_mm\n10,0.01\n20,0.02\n40,0.04\n80,0.08\n");
    EXPECT_EQ(almen_fit_job(o, out, err), kExitInputError);
    EXPECT_NE(err.str().find("no saturation point"), std::string::npos) << err.str();
    err.str("");
    o.curve_path = write(dir.path / "ok.csv", exact_curve_csv({1, 2, 4, 8, 16}));
    o.strip = "B";
    EXPECT_EQ(almen_fit_job(o, out, err), kExitInputError);
    EXPECT_NE(err.str().find("--strip: expected A, N or C"), std::string::npos) << err.str();
    err.str("");
    o.strip = "";
    o.calibrate_run = dir.path.string();  // not a run
    EXPECT_EQ(almen_fit_job(o, out, err), kExitInputError);
    EXPECT_NE(err.str().find("is not a peensim run directory"), std::string::npos) << err.str();
    err.str("");
    o.curve_path = write(dir.path / "passes.csv", "passes,arc_height_thou\n1,6\n2,9\n4,11\n8,12\n");
    EXPECT_EQ(almen_fit_job(o, out, err), kExitInputError);
    EXPECT_NE(err.str().find("--calibrate needs exposure as a time"), std::string::npos) << err.str();
}

// A run of scenes/almen.yaml (0.6 s) into `dir`, analysed.
void run_almen(const fs::path& dir, const std::vector<std::string>& overrides) {
    RunOptions o;
    o.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/almen.yaml";
    o.output_dir = dir.string();
    o.progress = false;
    o.overrides = overrides;
    o.overrides.push_back("process.duration=0.6 s");
    std::ostringstream out, err;
    ASSERT_EQ(run_job(o, out, err), kExitOk) << err.str();
}

nlohmann::json strip_figures(const fs::path& run) {
    return nlohmann::json::parse(read_file(run / "analysis" / "figures.json"))["components"][0];
}

// A column name in Latin-1 (not UTF-8) made --json fail with exit 1 (found by the fuzz suite): its
// bytes are replaced in the JSON, the figures written.
TEST(AlmenFitJob, AColumnNameThatIsNotUtf8StillGivesItsJson) {
    TempDir dir;
    AlmenFitOptions o;
    o.curve_path = write(dir.path / "latin1.csv", "time_min,arc \xB5 height_in\n4,0.0060\n6,0.0069\n8,0.0070\n12,0.0070\n");
    o.json_path = (dir.path / "fit.json").string();
    std::ostringstream out, err;
    ASSERT_EQ(almen_fit_job(o, out, err), kExitOk) << err.str();
    const nlohmann::json j = nlohmann::json::parse(read_file(o.json_path));
    EXPECT_EQ(j["height_column"], "arc \xEF\xBF\xBD height_in");  // U+FFFD for the byte
    EXPECT_EQ(j["used"], "2P");
}

TEST(AlmenFitJob, CalibrationRoundTripThroughRuns) {
    TempDir dir;
    const fs::path cal_run = dir.path / "cal";
    run_almen(cal_run, {});
    const nlohmann::json cal_figures = strip_figures(cal_run);
    ASSERT_TRUE(cal_figures["almen_dent_size_m"].is_number());
    EXPECT_TRUE(cal_figures["almen_predicted_intensity_m"].is_null());  // not calibrated yet

    // A measured curve in seconds and mm: a = 0.25 mm, b = 0.01 /s.
    std::string csv = "time_s,arc_height_mm\n";
    for (double t : {30.0, 60.0, 120.0, 180.0, 240.0, 360.0, 480.0, 720.0})
        csv += exact(t) + "," + exact(0.25 * -std::expm1(-0.01 * t)) + "\n";
    AlmenFitOptions o;
    o.curve_path = write(dir.path / "measured.csv", csv);
    o.calibrate_run = cal_run.string();
    o.strip = "A";
    o.json_path = (dir.path / "fit.json").string();
    std::ostringstream out, err;
    ASSERT_EQ(almen_fit_job(o, out, err), kExitOk) << err.str();
    EXPECT_NE(out.str().find("      calibration:\n        saturation_arc_height: "), std::string::npos) << out.str();
    const std::size_t set = out.str().find("--set \"");
    ASSERT_NE(set, std::string::npos) << out.str();
    const std::size_t from = set + 7, to = out.str().find('"', from);
    const std::string calibration = out.str().substr(from, to - from);  // as printed for the command line
    EXPECT_EQ(calibration.rfind("components[almen].almen.calibration={", 0), 0u) << calibration;
    const nlohmann::json fit = nlohmann::json::parse(read_file(o.json_path));
    EXPECT_EQ(fit["calibration"]["dent_size_m"].get<double>(), cal_figures["almen_dent_size_m"].get<double>());

    // The same run, calibrated: the measured curve back.
    const fs::path same = dir.path / "same";
    run_almen(same, {calibration});
    const nlohmann::json back = strip_figures(same);
    const double measured_T = std::log(10.0) / fit["fits"][0]["b"].get<double>(), measured_I = fit["intensity_m"].get<double>();
    EXPECT_NEAR(back["almen_predicted_saturation_time_s"].get<double>() / measured_T, 1.0, 1e-12);
    EXPECT_NEAR(back["almen_predicted_intensity_m"].get<double>() / measured_I, 1.0, 1e-12);
    EXPECT_NEAR(measured_I, 0.9 * 0.25e-3, 1e-12);
    const std::string report = read_file(same / "analysis" / "report.md");
    EXPECT_NE(report.find("Against the calibration run: dent size x1, covering rate x1"), std::string::npos) << report;
    EXPECT_NE(report.find("(0.0089A)"), std::string::npos) << report;  // 0.225 mm = 0.00886 in

    // Another amplitude: the intensity moves with the dent size, the time with the covering rate.
    const fs::path loud = dir.path / "loud";
    run_almen(loud, {calibration, "components[sonotrode].vibration.amplitude=40 um"});
    const nlohmann::json l = strip_figures(loud);
    EXPECT_NEAR(l["almen_predicted_intensity_m"].get<double>() / measured_I,
                l["almen_dent_size_m"].get<double>() / cal_figures["almen_dent_size_m"].get<double>(), 1e-12);
    EXPECT_NEAR(l["almen_predicted_saturation_time_s"].get<double>() / measured_T,
                cal_figures["almen_covering_rate_per_s"].get<double>() / l["almen_covering_rate_per_s"].get<double>(), 1e-12);
    const std::string csv_loud = read_file(loud / "analysis" / "almen_almen.csv");
    EXPECT_EQ(csv_loud.substr(0, csv_loud.find('\n')), "time_s,dose_J_per_m2,arc_height_mm,dent_area_ratio,predicted_arc_height_mm");
}

}  // namespace
}  // namespace peensim
