// report.html's 3D view of a part (app/analysis/report_views.h, output/part_view_html.h), end to
// end on a short gear run: the page holds the view and its library inline, and in headless
// Chromium it draws the part, and a pick of a triangle reads that triangle's values as the
// triangles CSV gives them. Without the library the report says what to install.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/analysis/analyze_job.h"
#include "app/analysis/report_views.h"
#include "app/run/run_job.h"
#include "app/sweep/sweep_job.h"
#include "common/csv_column.h"
#include "support/csv_columns.h"
#include "support/shell_command.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using peensim::testing::TempDir;

namespace peensim {
namespace report_view_cases {

std::string read_all(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// A 0.3 s run of the shipped gear, analysed.
void analysed_gear(const fs::path& dir) {
    RunOptions o;
    o.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/gear.yaml";
    o.output_dir = dir.string();
    o.overrides = {"process.duration=0.3"};
    o.progress = false;
    o.analyze = false;
    std::ostringstream out, err;
    ASSERT_EQ(run_job(o, out, err), kExitOk) << err.str();
    ASSERT_EQ(analyze_job(dir.string(), out, err), kExitOk) << err.str();
}

// The headless browser the test drives (CI installs chromium-headless-shell), or "" for none.
std::string headless_browser() {
    for (const char* b : {"/usr/bin/chromium-headless-shell", "/usr/lib/chromium/chromium-headless-shell", "/usr/bin/chromium"})
        if (fs::exists(b)) return b;
    return "";
}

// The page's DOM once headless Chromium (software WebGL) has drawn it and run the pick the
// fragment asks for (part_view_js.h's test hook); "" when the browser failed.
std::string page_after_pick(const std::string& browser, const fs::path& page, const std::string& fragment) {
    const auto r = testing::run_shell("'" + browser +
                                      "' --headless --no-sandbox --disable-gpu --enable-unsafe-swiftshader --use-angle=swiftshader "
                                      "--virtual-time-budget=20000 --dump-dom 'file://" +
                                      page.string() + "#" + fragment + "' 2>/dev/null");
    EXPECT_EQ(r.status, 0) << r.output.substr(0, 2000);
    return r.status == 0 ? r.output : std::string();
}

// The value of the first attribute `name` in the DOM ("" for none).
std::string attribute_in(const std::string& dom, const std::string& name) {
    std::smatch m;
    const std::regex re(name + "=\"([^\"]*)\"");
    return std::regex_search(dom, m, re) ? m[1].str() : std::string();
}

// What the pick read, by field name (NaN where the view has no value): the info element's
// data-fields and data-values, their quotes HTML-escaped in the DOM.
std::map<std::string, double> picked_values(const std::string& dom) {
    const auto unescaped = [](std::string text) {
        for (std::size_t at; (at = text.find("&quot;")) != std::string::npos;) text.replace(at, 6, "\"");
        return text;
    };
    const auto names = nlohmann::json::parse(unescaped(attribute_in(dom, "data-fields")));
    const auto values = nlohmann::json::parse(attribute_in(dom, "data-values"));
    std::map<std::string, double> picked;
    for (std::size_t k = 0; k < names.size() && k < values.size(); ++k)
        picked[names[k].get<std::string>()] = values[k].is_number() ? values[k].get<double>() : std::nan("");
    return picked;
}

TEST(ReportView, TheReportHoldsAViewOfEachPartWithItsLibraryInline) {
    if (!fs::exists(std::string(kThreeJsDir) + "/three.min.js")) GTEST_SKIP() << "libjs-three is not installed";
    TempDir dir;
    analysed_gear(dir.path);
    const std::string md = read_all(dir.path / "analysis" / "report.md");
    EXPECT_NE(md.find("## The parts in 3D"), std::string::npos);
    EXPECT_NE(md.find("<!-- 3D view: gear -->"), std::string::npos);
    const std::string html = read_all(dir.path / "analysis" / "report.html");
    EXPECT_EQ(html.find("<!-- 3D view: gear -->"), std::string::npos) << "the marker is replaced by the view";
    EXPECT_NE(html.find("<div class=\"pv\" data-part=\"gear\">"), std::string::npos);
    EXPECT_NE(html.find("OrbitControls"), std::string::npos);
    EXPECT_NE(html.find("peensimPartView"), std::string::npos);
    EXPECT_EQ(html.find("<script src="), std::string::npos) << "one file that opens offline";
    // The view's data: the mesh of the gear (4,960 triangles, not thinned) and its fields (a 0.3 s run
    // is too short for a time to the target: that field, empty, is not offered).
    const std::size_t open = html.find("<script type=\"application/json\">"), close = html.find("</script>", open);
    ASSERT_NE(open, std::string::npos);
    const auto data = nlohmann::json::parse(html.substr(open + 32, close - open - 32));
    EXPECT_EQ(data["name"], "gear");
    std::vector<std::string> names;
    for (const auto& f : data["fields"]) names.push_back(f["name"]);
    // The region's time to the target is offered when some region has one (reached or forecast).
    const std::vector<std::string> status = read_csv_texts(dir.path / "analysis" / "gear_regions.csv", "time_to_target_status");
    const bool timed = std::any_of(status.begin(), status.end(), [](const std::string& x) { return x == "reached" || x == "forecast"; });
    std::vector<std::string> expected{"coverage", "coverage_smoothed", "impacts_per_mm2_s_smoothed", "mean_vn_mps_smoothed"};
    if (timed) expected.push_back("region_time_to_target_s");
    expected.push_back("region");
    EXPECT_EQ(names, expected);
    EXPECT_DOUBLE_EQ(data["fields"][0]["target"].get<double>(), 98.0);
    EXPECT_EQ(data["fields"].back()["categorical"], true);
    EXPECT_EQ(names[data["shown"].get<std::size_t>()], "impacts_per_mm2_s_smoothed")
        << "far below the target: where the impacts land first";
    EXPECT_EQ(data["regions"].size(), 21u);  // the 20 teeth and the bore
}

TEST(ReportView, WithoutTheLibraryTheReportSaysWhatToInstall) {
    TempDir dir;
    ::setenv("PEENSIM_THREE_JS", (dir.path / "no-three-here").c_str(), 1);
    analysed_gear(dir.path);
    ::unsetenv("PEENSIM_THREE_JS");
    const std::string md = read_all(dir.path / "analysis" / "report.md");
    EXPECT_NE(md.find("apt-get install libjs-three"), std::string::npos);
    EXPECT_EQ(read_all(dir.path / "analysis" / "report.html").find("class=\"pv\""), std::string::npos);
}

TEST(ReportView, InAHeadlessBrowserThePartIsDrawnAndAPickReadsTheTrianglesValues) {
    const std::string browser = headless_browser();
    if (browser.empty() || !fs::exists(std::string(kThreeJsDir) + "/three.min.js"))
        GTEST_SKIP() << "needs chromium-headless-shell and libjs-three (CI installs both)";
    TempDir dir;
    analysed_gear(dir.path);
    // The most hit triangle of the gear: on the outside, where a shot can reach.
    const auto csv = testing::read_csv_columns(dir.path / "analysis" / "gear_triangles.csv");
    const std::vector<double>& impacts = csv.at("impacts");
    std::size_t t = 0;
    for (std::size_t k = 0; k < impacts.size(); ++k)
        if (impacts[k] > impacts[t]) t = k;
    ASSERT_GT(impacts[t], 0.0);
    const fs::path page = dir.path / "analysis" / "report.html";
    const std::string dom = page_after_pick(browser, page, "pick=0:" + std::to_string(t));
    ASSERT_FALSE(dom.empty());
    const auto attribute = [&](const std::string& name) { return attribute_in(dom, name); };
    ASSERT_EQ(attribute("data-error"), "");
    EXPECT_EQ(attribute("data-views-ready"), "1");
    EXPECT_EQ(attribute("data-picked"), "yes");
    EXPECT_GT(std::stol("0" + attribute("data-lit-pixels")), 10000) << "the part is drawn";
    ASSERT_EQ(attribute("data-triangle"), std::to_string(t));
    // Its values, as the triangles CSV has them (the CSV rounds to 4-6 digits; the view holds floats).
    auto v = picked_values(dom);
    ASSERT_GE(v.size(), 5u);
    EXPECT_NEAR(v["coverage"], 100.0 * csv.at("coverage")[t], 1e-3 * std::max(1.0, 100.0 * csv.at("coverage")[t]));
    EXPECT_NEAR(v["coverage_smoothed"], 100.0 * csv.at("coverage_smoothed")[t],
                1e-3 * std::max(1.0, 100.0 * csv.at("coverage_smoothed")[t]));
    EXPECT_NEAR(v["impacts_per_mm2_s_smoothed"], csv.at("impacts_per_mm2_s_smoothed")[t], 1e-3 * csv.at("impacts_per_mm2_s_smoothed")[t]);
    EXPECT_NEAR(v["mean_vn_mps_smoothed"], csv.at("mean_vn_mps_smoothed")[t], 1e-3 * csv.at("mean_vn_mps_smoothed")[t]);
    EXPECT_FALSE(attribute("data-region").empty());
}

// A sweep's report.html: the variants side by side in one view; a pick on the second variant's
// triangle reads the mean of that variant's runs (two seeds) from their triangles CSVs.
TEST(ReportView, ASweepsVariantsSideBySideReadTheirOwnRunsMeans) {
    const std::string browser = headless_browser();
    if (browser.empty() || !fs::exists(std::string(kThreeJsDir) + "/three.min.js"))
        GTEST_SKIP() << "needs chromium-headless-shell and libjs-three (CI installs both)";
    TempDir dir;
    SweepOptions o;
    o.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/gear.yaml";
    o.output_dir = dir.path.string();
    o.vary = {"components[sonotrode].vibration.amplitude=40 um,80 um"};
    o.overrides = {"process.duration=0.3"};
    o.seeds = 2;
    o.executable = PEENSIM_BINARY;
    std::ostringstream out, err;
    ASSERT_EQ(sweep_job(o, out, err), kExitOk) << err.str();
    const fs::path page = dir.path / "sweep" / "report.html";
    ASSERT_TRUE(fs::exists(page));
    EXPECT_NE(read_all(dir.path / "sweep" / "report.md").find("<!-- 3D view: variants -->"), std::string::npos);
    // The second variant's most hit triangle in its first run.
    const auto first = testing::read_csv_columns(dir.path / "amplitude-80um" / "s0" / "analysis" / "gear_triangles.csv");
    const auto second = testing::read_csv_columns(dir.path / "amplitude-80um" / "s1" / "analysis" / "gear_triangles.csv");
    std::size_t t = 0;
    for (std::size_t k = 0; k < first.at("impacts").size(); ++k)
        if (first.at("impacts")[k] > first.at("impacts")[t]) t = k;
    const std::string dom = page_after_pick(browser, page, "pick=0:" + std::to_string(t) + ":1");
    ASSERT_FALSE(dom.empty());
    const auto attribute = [&](const std::string& name) { return attribute_in(dom, name); };
    EXPECT_EQ(attribute("data-picked"), "yes");
    EXPECT_GT(std::stol("0" + attribute("data-lit-pixels")), 10000);
    EXPECT_EQ(attribute("data-instance"), "amplitude-80um");
    ASSERT_EQ(attribute("data-triangle"), std::to_string(t));
    auto v = picked_values(dom);
    const auto mean = [&](const std::string& column, double scale) { return 0.5 * scale * (first.at(column)[t] + second.at(column)[t]); };
    EXPECT_NEAR(v["coverage"], mean("coverage", 100.0), 1e-3 * std::max(1.0, mean("coverage", 100.0)));
    EXPECT_NEAR(v["impacts_per_mm2_s_smoothed"], mean("impacts_per_mm2_s_smoothed", 1.0), 1e-3 * mean("impacts_per_mm2_s_smoothed", 1.0));
    EXPECT_NEAR(v["mean_vn_mps_smoothed"], mean("mean_vn_mps_smoothed", 1.0), 1e-3 * mean("mean_vn_mps_smoothed", 1.0));
    // The point in the part's own frame, as in a run of that variant alone (the copies sit side by
    // side in the view): inside the gear's box, not shifted along x.
    const auto point = nlohmann::json::parse(attribute("data-point"));
    EXPECT_LT(std::abs(point[0].get<double>()), 40.0) << point.dump();
}

}  // namespace report_view_cases
}  // namespace peensim
