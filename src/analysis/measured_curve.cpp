#include "analysis/measured_curve.h"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>

#include "common/input_error.h"
#include "common/text_excerpt.h"

namespace peensim {

namespace {

std::string lower(std::string s) {
    for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return s;
}

// The words of a column name: runs of letters, digits and non-ASCII bytes (so "µm" is a word).
std::vector<std::string> words_of(const std::string& name) {
    std::vector<std::string> words;
    std::string word;
    for (const char ch : name) {
        const auto u = static_cast<unsigned char>(ch);
        if (std::isalnum(u) || u >= 0x80) {
            word += static_cast<char>(std::tolower(u));
        } else if (!word.empty()) {
            words.push_back(word);
            word.clear();
        }
    }
    if (!word.empty()) words.push_back(word);
    return words;
}

// A field of a line and the column (1-based) it starts at.
struct Field {
    std::string text;
    int column = 1;
};

std::vector<Field> split_fields(const std::string& line) {
    std::vector<Field> fields;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = line.find(',', start);
        const std::size_t end = comma == std::string::npos ? line.size() : comma;
        std::size_t a = start, b = end;
        while (a < b && std::isspace(static_cast<unsigned char>(line[a]))) ++a;
        while (b > a && std::isspace(static_cast<unsigned char>(line[b - 1]))) --b;
        fields.push_back({line.substr(a, b - a), static_cast<int>(a) + 1});
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return fields;
}

template <class Unit>
Unit unit_of_column(const std::string& path, int line, const Field& header, const std::string& option, const char* option_name,
                    std::optional<Unit> (*named)(const std::string&), const char* expected) {
    std::optional<Unit> from_header;
    for (const std::string& w : words_of(header.text))
        if (const auto u = named(w)) from_header = u;  // the last unit word counts
    std::optional<Unit> from_option;
    if (!option.empty()) {
        from_option = named(lower(option));
        if (!from_option)
            throw InputError(kCommandLine, option_name, "expected one of " + std::string(expected) + ", got " + text_excerpt(option));
    }
    if (from_header && from_option && from_header->name != from_option->name)
        throw InputError({path, line, header.column}, header.text,
                         "the column name says " + from_header->name + " but " + option_name + " says " + from_option->name +
                             " (give one, or make them agree)");
    if (from_option) return *from_option;
    if (from_header) return *from_header;
    throw InputError({path, line, header.column}, header.text,
                     "expected a unit in the column name (" + std::string(expected) + ", e.g. " +
                         (std::strcmp(option_name, "--time-unit") == 0 ? "time_min" : "arc_height_in") + ") or the option " + option_name);
}

// A finite number, or an InputError naming the field.
double number_in(const std::string& path, int line, const Field& f, const std::string& column, const std::string& what) {
    double v = 0.0;
    const char* first = f.text.data();
    const char* last = first + f.text.size();
    if (!f.text.empty() && *first == '+') ++first;
    const auto [end, ec] = std::from_chars(first, last, v);
    if (f.text.empty() || ec != std::errc() || end != last || !std::isfinite(v))
        throw InputError({path, line, f.column}, column, "expected a number (" + what + "), got " + text_excerpt(f.text));
    return v;
}

// The next line (without its '\n') into `line`; false at the end of the file. A line longer than
// kMaxCurveLineBytes is refused (a binary file or a runaway line is never read whole).
bool read_line(std::istream& in, std::string& line, const std::string& path, int number) {
    line.clear();
    std::streambuf& buffer = *in.rdbuf();
    for (int c = buffer.sbumpc(); c != std::char_traits<char>::eof(); c = buffer.sbumpc()) {
        if (c == '\n') return true;
        if (line.size() == kMaxCurveLineBytes)
            throw InputError({path, number, 0}, "",
                             "a line longer than " + std::to_string(kMaxCurveLineBytes) + " bytes (it begins " + text_excerpt(line) +
                                 "); expected a CSV line of exposure, arc height");
        line += static_cast<char>(c);
    }
    return !line.empty();
}

// A byte no text has: the file is not a CSV (a binary file, the wrong file). Its bytes are not
// printed, only an escaped excerpt.
void refuse_binary(const std::string& path, int number, const std::string& line) {
    if (!has_binary_byte(line)) return;
    std::size_t at = 0;
    while (!has_binary_byte(std::string_view(line).substr(at, 1))) ++at;
    char byte[8];
    std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(line[at]));
    throw InputError({path, number, static_cast<int>(at) + 1}, "",
                     std::string("expected a text CSV file (a header, then exposure, arc height per line), got the byte ") + byte +
                         " (binary data?) in " + text_excerpt(line));
}

}  // namespace

std::optional<ExposureUnit> exposure_unit_named(const std::string& word) {
    static const std::pair<const char*, ExposureUnit> units[] = {
        {"s", {"s", 1.0}},           {"sec", {"s", 1.0}},       {"secs", {"s", 1.0}},        {"second", {"s", 1.0}},
        {"seconds", {"s", 1.0}},     {"min", {"min", 60.0}},    {"mins", {"min", 60.0}},     {"minute", {"min", 60.0}},
        {"minutes", {"min", 60.0}},  {"h", {"h", 3600.0}},      {"hr", {"h", 3600.0}},       {"hour", {"h", 3600.0}},
        {"hours", {"h", 3600.0}},    {"pass", {"passes", 0.0}}, {"passes", {"passes", 0.0}}, {"cycle", {"cycles", 0.0}},
        {"cycles", {"cycles", 0.0}},
    };
    for (const auto& [name, unit] : units)
        if (word == name) return unit;
    return std::nullopt;
}

std::optional<HeightUnit> height_unit_named(const std::string& word) {
    static const std::pair<const char*, HeightUnit> units[] = {
        {"mm", {"mm", 1e-3}},          {"um", {"um", 1e-6}},         {"\xC2\xB5m", {"um", 1e-6}},  // µm
        {"\xCE\xBCm", {"um", 1e-6}},                                                               // μm (Greek mu)
        {"in", {"in", 0.0254}},        {"inch", {"in", 0.0254}},     {"inches", {"in", 0.0254}},
        {"thou", {"thou", 0.0000254}}, {"mil", {"thou", 0.0000254}}, {"mils", {"thou", 0.0000254}},
    };
    for (const auto& [name, unit] : units)
        if (word == name) return unit;
    return std::nullopt;
}

int MeasuredCurve::distinct_exposures() const {
    std::set<double> e;
    for (const SaturationDatum& p : points)
        if (p.exposure > 0.0) e.insert(p.exposure);
    return static_cast<int>(e.size());
}

MeasuredCurve read_measured_curve(const std::string& path, const std::string& time_unit, const std::string& height_unit) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError({path, 0, 0}, "", std::string("cannot open the curve file: ") + std::strerror(errno));
    MeasuredCurve curve;
    curve.path = path;
    std::string line;
    int number = 0;
    bool header = false;
    while (read_line(in, line, path, number + 1)) {
        ++number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (number == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);  // a UTF-8 byte-order mark
        refuse_binary(path, number, line);
        std::size_t first = 0;
        while (first < line.size() && std::isspace(static_cast<unsigned char>(line[first]))) ++first;
        if (first == line.size() || line[first] == '#') continue;
        const std::vector<Field> fields = split_fields(line);
        if (!header) {
            if (fields.size() != 2)
                throw InputError(
                    {path, number, 1}, "header",
                    "expected two column names (exposure, arc height; e.g. time_min,arc_height_in), got " + std::to_string(fields.size()));
            for (const Field& f : fields) {
                double ignored = 0.0;
                const auto [end, ec] = std::from_chars(f.text.data(), f.text.data() + f.text.size(), ignored);
                if (!f.text.empty() && ec == std::errc() && end == f.text.data() + f.text.size())
                    throw InputError(
                        {path, number, f.column}, "header",
                        "expected a header line of column names (e.g. time_min,arc_height_in), got the number " + text_excerpt(f.text));
            }
            curve.exposure_column = fields[0].text;
            curve.height_column = fields[1].text;
            curve.exposure_unit = unit_of_column<ExposureUnit>(path, number, fields[0], time_unit, "--time-unit", exposure_unit_named,
                                                               "s, min, h, passes or cycles");
            curve.height_unit =
                unit_of_column<HeightUnit>(path, number, fields[1], height_unit, "--height-unit", height_unit_named, "mm, um, in or thou");
            header = true;
            continue;
        }
        if (fields.size() != 2)
            throw InputError(
                {path, number, 1}, "row",
                "expected 2 fields (" + curve.exposure_column + ", " + curve.height_column + "), got " + std::to_string(fields.size()));
        const double t = number_in(path, number, fields[0], curve.exposure_column, "the exposure in " + curve.exposure_unit.name);
        const double h = number_in(path, number, fields[1], curve.height_column, "the arc height in " + curve.height_unit.name);
        if (t < 0.0)
            throw InputError({path, number, fields[0].column}, curve.exposure_column,
                             "expected an exposure >= 0, got " + text_excerpt(fields[0].text));
        if (h < 0.0)
            throw InputError({path, number, fields[1].column}, curve.height_column,
                             "expected an arc height >= 0, got " + text_excerpt(fields[1].text));
        if (curve.points.size() == kMaxCurveRows)
            throw InputError({path, number, 0}, "",
                             "more than " + std::to_string(kMaxCurveRows) +
                                 " rows of strips; expected a saturation curve (one row per strip: SAE J443 asks for 4 or more)");
        curve.points.push_back({t, h * curve.height_unit.metres});
        curve.lines.push_back(number);
    }
    if (!header)
        throw InputError({path, number + 1, 0}, "header", "expected a header line (e.g. time_min,arc_height_in), got an empty file");
    if (curve.points.empty())
        throw InputError({path, number + 1, 0}, "",
                         "expected rows of " + curve.exposure_column + "," + curve.height_column + " after the header, got none");
    if (curve.distinct_exposures() < 2)
        throw InputError({path, curve.lines.back(), 0}, curve.exposure_column,
                         "expected at least 2 different exposures > 0 to fit a saturation curve (SAE J443 asks for 4 or more), got " +
                             std::to_string(curve.distinct_exposures()));
    return curve;
}

}  // namespace peensim
