// The analysis PNG plots: gnuplot renders real 800x600 PNGs from small hand-written CSVs, keeps the
// scripts, copes with an empty histogram and awkward component names, and without gnuplot on PATH
// leaves no PNG but a note saying how to get them.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "app/analysis/analysis_plots.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using peensim::testing::TempDir;
using namespace peensim;

namespace {

// Sets PATH for the scope of the object, restoring it after.
struct PathOverride {
    std::string saved;
    explicit PathOverride(const std::string& path) : saved(std::getenv("PATH") ? std::getenv("PATH") : "") {
        setenv("PATH", path.c_str(), 1);
    }
    ~PathOverride() { setenv("PATH", saved.c_str(), 1); }
};

void write_plot_input(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

void write_csvs(const fs::path& dir, const std::string& component, bool with_dents) {
    write_plot_input(dir / (component + "_coverage.csv"), "time_s,coverage\n0,0\n0.1,0.3\n0.2,0.55\n0.3,0.7\n0.4,0.81\n");
    std::string h =
        "region,quantity,bin_low,bin_high,unit,count\n"
        "all,normal_speed,0,0.25,m/s,3\nall,normal_speed,0.25,0.5,m/s,12\nall,normal_speed,0.5,0.75,m/s,7\n"
        "all,impact_angle,0,5,deg,4\nall,impact_angle,5,10,deg,9\nall,impact_angle,10,15,deg,9\n";
    if (with_dents) h += "all,dent_diameter,100,110,um,5\nall,dent_diameter,110,120,um,17\n";
    h += "tooth0,normal_speed,0,0.25,m/s,3\n";  // a region's rows: not in the whole-component panels
    write_plot_input(dir / (component + "_histograms.csv"), h);
}

struct PngInfo {
    bool signature_ok = false;
    std::uint32_t width = 0, height = 0;  // pixels, from the IHDR chunk
};

PngInfo read_png_info(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    const std::vector<unsigned char> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    PngInfo info;
    if (b.size() < 24) return info;
    const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    info.signature_ok = std::equal(signature, signature + 8, b.begin()) && std::string(b.begin() + 12, b.begin() + 16) == "IHDR";
    auto be32 = [&](std::size_t at) {
        return std::uint32_t{b[at]} << 24 | std::uint32_t{b[at + 1]} << 16 | std::uint32_t{b[at + 2]} << 8 | b[at + 3];
    };
    info.width = be32(16);
    info.height = be32(20);
    return info;
}

bool gnuplot_installed() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

}  // namespace

TEST(AnalysisPlots, RendersCoverageAndHistogramPngsOfTheRequestedSize) {
    if (!gnuplot_installed()) GTEST_SKIP() << "gnuplot not installed (.ci/install-deps installs gnuplot-nox)";
    TempDir dir;
    write_csvs(dir.path, "gear", true);
    std::string note = "stale";
    const std::vector<std::string> pngs = write_analysis_plots(dir.path.string(), {"gear"}, 0.98, note);
    EXPECT_EQ(note, "");
    ASSERT_EQ(pngs.size(), 2u);
    EXPECT_EQ(pngs[0], (dir.path / "gear_coverage.png").string());
    EXPECT_EQ(pngs[1], (dir.path / "gear_histograms.png").string());
    for (const std::string& png : pngs) {
        const PngInfo info = read_png_info(png);
        EXPECT_TRUE(info.signature_ok) << png;
        EXPECT_EQ(info.width, static_cast<std::uint32_t>(kPlotWidthPx)) << png;
        EXPECT_EQ(info.height, static_cast<std::uint32_t>(kPlotHeightPx)) << png;
        EXPECT_FALSE(fs::exists(png + ".tmp")) << png;
    }
    // The scripts stay, for users to edit, and name their CSVs relative to the analysis dir.
    std::ifstream script(dir.path / "gear_histograms.gp");
    const std::string text((std::istreambuf_iterator<char>(script)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("'gear_histograms.csv'"), std::string::npos);
    EXPECT_NE(text.find("dent diameter"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir.path / "gear_coverage.gp"));
}

TEST(AnalysisPlots, RegionAndAlmenPlotsWhenTheirTablesExist) {
    if (!gnuplot_installed()) GTEST_SKIP() << "gnuplot not installed";
    TempDir dir;
    write_plot_input(dir.path / "gear_regions.csv",
                     "region,triangles,area_mm2,impacts,impacts_per_mm2_s,mean_vn_mps,max_vn_mps,energy_J_per_m2,coverage\n"
                     "tooth0,10,20.5,30,0.3,1.5,3,0.01,0.2\ntooth1,10,20.5,60,0.6,2.5,4,0.02,0.4\n");
    write_plot_input(dir.path / "strip_almen.csv", "time_s,dose_J_per_m2,arc_height_mm\n0,0,0\n1,2,0.05\n2,4,0.09\n");
    write_plot_input(dir.path / "bare_almen.csv", "time_s,dose_J_per_m2,arc_height_mm\n0,0,\n1,2,\n2,4,\n");
    write_plot_input(
        dir.path / "model_almen.csv",
        "time_s,dose_J_per_m2,arc_height_mm,dent_area_ratio,predicted_arc_height_mm\n0,0,,0,0\n1,2,,0.1,0.04\n2,4,,0.2,0.07\n");
    std::string note;
    const std::vector<std::string> pngs = write_analysis_plots(dir.path.string(), {"gear", "strip", "bare", "model"}, 0.98, note);
    EXPECT_EQ(note, "");
    ASSERT_EQ(pngs.size(), 4u);
    EXPECT_EQ(pngs[0], (dir.path / "gear_regions.png").string());
    EXPECT_EQ(pngs[1], (dir.path / "strip_almen.png").string());
    EXPECT_EQ(pngs[2], (dir.path / "bare_almen.png").string());
    for (const std::string& png : pngs) EXPECT_TRUE(read_png_info(png).signature_ok) << png;
    std::ifstream calibrated(dir.path / "strip_almen.gp"), bare(dir.path / "bare_almen.gp");
    const std::string with((std::istreambuf_iterator<char>(calibrated)), std::istreambuf_iterator<char>());
    const std::string without((std::istreambuf_iterator<char>(bare)), std::istreambuf_iterator<char>());
    EXPECT_NE(with.find("arc height (calibrated)"), std::string::npos);
    EXPECT_NE(without.find("not calibrated"), std::string::npos);
    std::ifstream predicted(dir.path / "model_almen.gp");
    const std::string model((std::istreambuf_iterator<char>(predicted)), std::istreambuf_iterator<char>());
    EXPECT_NE(model.find("using 1:5 every ::1 axes x1y2"), std::string::npos) << model;
    EXPECT_NE(model.find("arc height (predicted)"), std::string::npos);
}

TEST(AnalysisPlots, EmptyHistogramPanelAndQuotedNamesStillRender) {
    if (!gnuplot_installed()) GTEST_SKIP() << "gnuplot not installed";
    TempDir dir;
    const std::string name = "Tom's gear_1";  // a quote for the shell and gnuplot, an _ for enhanced text
    write_csvs(dir.path, name, false);        // no dent rows: material without yield_stress
    std::string note;
    const std::vector<std::string> pngs = write_analysis_plots(dir.path.string(), {name}, 0.98, note);
    EXPECT_EQ(note, "");
    ASSERT_EQ(pngs.size(), 2u);
    for (const std::string& png : pngs) EXPECT_TRUE(read_png_info(png).signature_ok) << png;
}

TEST(AnalysisPlots, MissingCsvsGiveNoPlotAndNoError) {
    if (!gnuplot_installed()) GTEST_SKIP() << "gnuplot not installed";
    TempDir dir;
    write_plot_input(dir.path / "rod_histograms.csv", "region,quantity,bin_low,bin_high,unit,count\nall,normal_speed,0,0.25,m/s,2\n");
    std::string note;
    const std::vector<std::string> pngs = write_analysis_plots(dir.path.string(), {"rod", "absent"}, 0.98, note);
    EXPECT_EQ(note, "");
    ASSERT_EQ(pngs.size(), 1u);  // rod has no coverage CSV (no yield stress), "absent" nothing
    EXPECT_EQ(pngs[0], (dir.path / "rod_histograms.png").string());
}

TEST(AnalysisPlots, WithoutGnuplotOnPathNoPngAndANote) {
    TempDir dir;
    write_csvs(dir.path, "gear", true);
    std::string note;
    std::vector<std::string> pngs;
    {
        const PathOverride empty_path(dir.path.string());  // a directory without gnuplot
        pngs = write_analysis_plots(dir.path.string(), {"gear"}, 0.98, note);
    }
    EXPECT_TRUE(pngs.empty());
    EXPECT_EQ(note, kNoGnuplotNote);
    EXPECT_FALSE(fs::exists(dir.path / "gear_coverage.png"));
    EXPECT_FALSE(fs::exists(dir.path / "gear_histograms.png"));
}
