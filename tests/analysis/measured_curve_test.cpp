// Reading a measured saturation curve (analysis/measured_curve.h): units from the header's names or
// the options, exact conversions (1 in = 25.4 mm, 1 thou = 0.0254 mm), comments and line endings,
// and bad files refused with their file, line, column, field and what was expected.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "analysis/measured_curve.h"
#include "common/input_error.h"
#include "support/temp_dir.h"

namespace peensim {
namespace {

using peensim::testing::TempDir;

std::string write(const TempDir& dir, const std::string& name, const std::string& text) {
    const std::string path = (dir.path / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

// The message of the InputError reading `text` throws ("" if none).
std::string error_of(const std::string& text, const std::string& time_unit = "", const std::string& height_unit = "") {
    TempDir dir;
    try {
        read_measured_curve(write(dir, "c.csv", text), time_unit, height_unit);
    } catch (const InputError& e) {
        const std::string m = e.what();
        return m.substr(m.find("c.csv"));
    }
    return "";
}

TEST(MeasuredCurve, UnitsComeFromTheHeaderNames) {
    TempDir dir;
    const MeasuredCurve c = read_measured_curve(write(dir, "a.csv", "time_min,arc_height_in\n1,0.006\n2,0.009\n4,0.011\n8,0.012\n"));
    EXPECT_EQ(c.exposure_unit.name, "min");
    EXPECT_EQ(c.exposure_unit.seconds, 60.0);
    EXPECT_EQ(c.height_unit.name, "in");
    ASSERT_EQ(c.points.size(), 4u);
    EXPECT_EQ(c.points[3].exposure, 8.0);  // minutes stay minutes
    EXPECT_EQ(c.points[3].arc_height, 0.012 * 0.0254);
    EXPECT_EQ(c.lines, (std::vector<int>{2, 3, 4, 5}));
    EXPECT_EQ(c.distinct_exposures(), 4);

    const struct {
        const char* header;
        const char* time;
        const char* height;
    } headers[] = {{"time (s),height (mm)", "s", "mm"},
                   {"passes,arc_height_thou", "passes", "thou"},
                   {"Exposure Minutes, Arc Height Inches", "min", "in"},
                   {"cycles,arc height um", "cycles", "um"},
                   {"t_h,h_mils", "h", "thou"},
                   {"time_seconds,arc_height_\xC2\xB5m", "s", "um"}};
    for (const auto& h : headers) {
        const MeasuredCurve k = read_measured_curve(write(dir, "h.csv", std::string(h.header) + "\n1,1\n2,2\n"));
        EXPECT_EQ(k.exposure_unit.name, h.time) << h.header;
        EXPECT_EQ(k.height_unit.name, h.height) << h.header;
        EXPECT_EQ(k.exposure_unit.is_time(), std::string(h.time) != "passes" && std::string(h.time) != "cycles");
    }
}

TEST(MeasuredCurve, ConversionsAreExact) {
    // 1 in = 25.4 mm and 1 thou = 0.001 in = 0.0254 mm, exactly (to the double).
    EXPECT_EQ(height_unit_named("in")->metres, 0.0254);
    EXPECT_EQ(height_unit_named("mm")->metres * 25.4, height_unit_named("in")->metres);
    EXPECT_EQ(height_unit_named("thou")->metres, 0.0000254);
    EXPECT_DOUBLE_EQ(height_unit_named("thou")->metres * 1000.0, height_unit_named("in")->metres);
    EXPECT_DOUBLE_EQ(height_unit_named("thou")->metres, 0.0254 * height_unit_named("mm")->metres);
    EXPECT_EQ(exposure_unit_named("min")->seconds, 60.0);
    EXPECT_EQ(exposure_unit_named("h")->seconds, 3600.0);
    EXPECT_FALSE(exposure_unit_named("passes")->is_time());
    // The same strips in thou and in inches read to the same metres.
    TempDir dir;
    const MeasuredCurve thou = read_measured_curve(write(dir, "t.csv", "time_s,arc_height_thou\n10,12\n20,16\n"));
    const MeasuredCurve inch = read_measured_curve(write(dir, "i.csv", "time_s,arc_height_in\n10,0.012\n20,0.016\n"));
    for (std::size_t k = 0; k < 2; ++k) EXPECT_DOUBLE_EQ(thou.points[k].arc_height, inch.points[k].arc_height);
}

TEST(MeasuredCurve, OptionsGiveMissingUnitsAndMustAgreeWithTheHeader) {
    TempDir dir;
    const std::string plain = write(dir, "p.csv", "exposure,arc height\n1,0.1\n2,0.2\n");
    const MeasuredCurve c = read_measured_curve(plain, "min", "mm");
    EXPECT_EQ(c.exposure_unit.name, "min");
    EXPECT_EQ(c.points[1].arc_height, 0.2 * 1e-3);
    EXPECT_EQ(read_measured_curve(write(dir, "q.csv", "time_min,arc_height_in\n1,1\n2,2\n"), "min", "in").height_unit.name, "in");
    EXPECT_EQ(
        error_of("exposure,arc height\n1,0.1\n2,0.2\n", "", "mm"),
        "c.csv:1:1: exposure: expected a unit in the column name (s, min, h, passes or cycles, e.g. time_min) or the option --time-unit");
    EXPECT_EQ(
        error_of("exposure,arc height\n1,0.1\n2,0.2\n", "min"),
        "c.csv:1:10: arc height: expected a unit in the column name (mm, um, in or thou, e.g. arc_height_in) or the option --height-unit");
    EXPECT_EQ(error_of("time_min,arc_height_in\n1,1\n2,2\n", "s"),
              "c.csv:1:1: time_min: the column name says min but --time-unit says s (give one, or make them agree)");
    TempDir d2;
    EXPECT_THROW(read_measured_curve(write(d2, "r.csv", "time_min,arc_height_in\n1,1\n2,2\n"), "fortnights"), InputError);
}

TEST(MeasuredCurve, CommentsBlankLinesCrlfAndAByteOrderMark) {
    TempDir dir;
    const MeasuredCurve c = read_measured_curve(write(dir, "c.csv",
                                                      "\xEF\xBB\xBF# measured 2026-11-20, S230 at 40 psi\r\n\r\n"
                                                      "time_min, arc_height_thou\r\n# first strip\r\n 2 , 6.1\r\n4,8.0\r\n\r\n8,+9.1\r\n"));
    ASSERT_EQ(c.points.size(), 3u);
    EXPECT_EQ(c.exposure_column, "time_min");
    EXPECT_EQ(c.height_column, "arc_height_thou");
    EXPECT_EQ(c.lines, (std::vector<int>{5, 6, 8}));
    EXPECT_DOUBLE_EQ(c.points[2].arc_height, 9.1 * 0.0000254);
}

TEST(MeasuredCurve, BadFilesAreRefusedWithTheirLine) {
    EXPECT_EQ(error_of(""), "c.csv:1: header: expected a header line (e.g. time_min,arc_height_in), got an empty file");
    EXPECT_EQ(error_of("# only a comment\n"), "c.csv:2: header: expected a header line (e.g. time_min,arc_height_in), got an empty file");
    EXPECT_EQ(error_of("1,0.006\n2,0.009\n"),
              "c.csv:1:1: header: expected a header line of column names (e.g. time_min,arc_height_in), got the number '1'");
    EXPECT_EQ(error_of("time_min,arc_height_in,strip\n"),
              "c.csv:1:1: header: expected two column names (exposure, arc height; e.g. time_min,arc_height_in), got 3");
    EXPECT_EQ(error_of("time_min,arc_height_in\n"), "c.csv:2: expected rows of time_min,arc_height_in after the header, got none");
    EXPECT_EQ(error_of("time_min,arc_height_in\n1,0.006\n2,0.009\n3,O.010\n"),
              "c.csv:4:3: arc_height_in: expected a number (the arc height in in), got 'O.010'");
    EXPECT_EQ(error_of("time_min,arc_height_in\n1,0.006\n,0.009\n"),
              "c.csv:3:1: time_min: expected a number (the exposure in min), got ''");
    EXPECT_EQ(error_of("time_min,arc_height_in\n1,0.006\n2,nan\n"),
              "c.csv:3:3: arc_height_in: expected a number (the arc height in in), got 'nan'");
    EXPECT_EQ(error_of("time_min,arc_height_in\n1,0.006\n2,inf\n"),
              "c.csv:3:3: arc_height_in: expected a number (the arc height in in), got 'inf'");
    EXPECT_EQ(error_of("time_min,arc_height_in\n1,0.006\n-2,0.009\n"), "c.csv:3:1: time_min: expected an exposure >= 0, got '-2'");
    EXPECT_EQ(error_of("time_min,arc_height_in\n1,0.006\n2,-0.009\n"),
              "c.csv:3:3: arc_height_in: expected an arc height >= 0, got '-0.009'");
    EXPECT_EQ(error_of("time_min,arc_height_in\n1,0.006\n2,0.009,0.010\n"),
              "c.csv:3:1: row: expected 2 fields (time_min, arc_height_in), got 3");
    EXPECT_EQ(
        error_of("time_min,arc_height_in\n0,0\n3,0.006\n3,0.0061\n"),
        "c.csv:4: time_min: expected at least 2 different exposures > 0 to fit a saturation curve (SAE J443 asks for 4 or more), got 1");
    TempDir dir;
    EXPECT_THROW(read_measured_curve((dir.path / "missing.csv").string()), InputError);
    // The header's line is its own, not line 1, when comments come first.
    EXPECT_EQ(
        error_of("# strips of 2026-11-20\nexposure,arc_height_in\n1,0.006\n2,0.009\n"),
        "c.csv:2:1: exposure: expected a unit in the column name (s, min, h, passes or cycles, e.g. time_min) or the option --time-unit");
}

// A binary file, or a line without end, is refused at its line without printing its bytes.
TEST(MeasuredCurve, BinaryBytesAndRunawayLinesAreRefusedWithAnExcerpt) {
    EXPECT_EQ(error_of(std::string("time_min,arc_height_in\n1,0.006\nab\x00\x01"
                                   "cd\n",
                                   38)),
              "c.csv:3:3: expected a text CSV file (a header, then exposure, arc height per line), got the byte 0x00 (binary data?) in "
              "'ab\\x00\\x01cd'");
    EXPECT_EQ(error_of("time_min,arc_height_in\n1," + std::string(5000, '7') + "\n"),
              "c.csv:2: a line longer than 4096 bytes (it begins '1," + std::string(38, '7') +
                  "'... (4096 bytes)); expected a CSV line of exposure, arc height");
    EXPECT_EQ(error_of("time_min,arc_height_in\n1,0.006\n2,0.0\xff"
                       "9\n"),
              "c.csv:3:3: arc_height_in: expected a number (the arc height in in), got '0.0\\xFF9'");
}

}  // namespace
}  // namespace peensim
