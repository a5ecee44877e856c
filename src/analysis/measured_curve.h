// A measured Almen saturation curve from a CSV file: a header, then one row per strip: exposure,
// arc height. Units come from the header's column names (the last unit word in each name:
// `time_min,arc_height_in`, `time (s),height (mm)`, `passes,arc_height_thou`) or from the caller
// (the command line's --time-unit, --height-unit); both given must agree.
//   exposure: s (sec, second, seconds), min (minute, minutes), h (hour, hours), or a count of
//             passes or cycles (pass, passes, cycle, cycles: no time unit)
//   arc height: mm, um, in (inch, inches), thou (mil, mils): 1 in = 25.4 mm, 1 thou = 0.001 in
// Blank lines and lines starting with `#` are skipped (a file may say where its data come from).
// Bad input is an InputError naming the file, line, column, field and what was expected; what the
// file holds is quoted as a short escaped excerpt (common/text_excerpt.h), never its raw bytes.
// Limits, checked as the file is read (before any fit): at most kMaxCurveRows rows of strips, lines
// of at most kMaxCurveLineBytes, text only (a control byte other than tab and CR: not a CSV).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "analysis/saturation_fit.h"

namespace peensim {

// A saturation curve has a row per strip (J443: 4 or more; a lab's replicates, tens): 10^5 rows
// are fitted in about a second, more are refused as the file is read.
inline constexpr std::size_t kMaxCurveRows = 100000;
inline constexpr std::size_t kMaxCurveLineBytes = 4096;  // bytes of one line, comments included

struct ExposureUnit {
    std::string name;      // as printed: "s", "min", "h", "passes", "cycles"
    double seconds = 0.0;  // s per unit; 0 for a count (passes, cycles)
    bool is_time() const { return seconds > 0.0; }
};

struct HeightUnit {
    std::string name;     // as printed: "mm", "um", "in", "thou"
    double metres = 0.0;  // m per unit (exact: 1 in = 0.0254 m)
};

// The unit a word names, or nullopt (words are matched lower-cased).
std::optional<ExposureUnit> exposure_unit_named(const std::string& word);
std::optional<HeightUnit> height_unit_named(const std::string& word);

struct MeasuredCurve {
    std::string path;
    ExposureUnit exposure_unit;
    HeightUnit height_unit;
    std::string exposure_column, height_column;  // the header's names
    // Exposure in the curve's own unit (min stays min: the saturation time is reported in it),
    // arc height in m. One point per row, in file order.
    std::vector<SaturationDatum> points;
    std::vector<int> lines;          // the file line of each point
    int distinct_exposures() const;  // distinct exposures > 0
};

// Reads and checks the file. time_unit / height_unit: the caller's unit words ("" = from the header).
// Throws InputError for a file that cannot be read as a curve (also: no data row, fewer than 2
// distinct exposures > 0, a negative or non-finite number, a missing or conflicting unit).
MeasuredCurve read_measured_curve(const std::string& path, const std::string& time_unit = "", const std::string& height_unit = "");

}  // namespace peensim
