#include "python/column_arrays.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string_view>

#include "analysis/impact_log_reader.h"
#include "output/impact_csv_writer.h"

namespace py = pybind11;

namespace peensim::python {

namespace {

// The array owns the vector's buffer through a capsule: NumPy frees it with the array.
template <class T>
py::array_t<T> adopt(std::vector<T>&& values) {
    auto* owned = new std::vector<T>(std::move(values));
    py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    return py::array_t<T>({static_cast<py::ssize_t>(owned->size())}, {static_cast<py::ssize_t>(sizeof(T))}, owned->data(), owner);
}

// One field of a CSV row: its text, and whether it was quoted (then it is text, whatever it reads as).
struct Field {
    std::string text;
    bool quoted = false;
};

// RFC 4180 fields: a quoted field may hold commas and doubled quotes ("[0, 0, -9.81]", "30 rpm").
std::vector<Field> split(std::string_view line) {
    std::vector<Field> fields(1);
    bool in_quotes = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (in_quotes) {
            if (c != '"') {
                fields.back().text += c;
            } else if (i + 1 < line.size() && line[i + 1] == '"') {
                fields.back().text += '"';
                ++i;
            } else {
                in_quotes = false;
            }
        } else if (c == '"') {
            in_quotes = true;
            fields.back().quoted = true;
        } else if (c == ',') {
            fields.emplace_back();
        } else if (c != '\r') {
            fields.back().text += c;
        }
    }
    return fields;
}

// The analysis' columns of counts and indices: int64. Every other number is float64, also when its
// values happen to be whole (a rate of 800 per s), so a column's type never depends on the run.
bool integer_column(std::string_view name) {
    for (std::string_view n : {"triangle", "facet", "impacts", "triangles", "count", "runs_finished", "shot"})
        if (name == n) return true;
    return false;
}

bool parse_int(std::string_view s, std::int64_t& out) {
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && p == s.data() + s.size() && !s.empty();
}

bool parse_double(std::string_view s, double& out) {
    if (s.empty()) {
        out = std::numeric_limits<double>::quiet_NaN();
        return true;
    }
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && p == s.data() + s.size();
}

}  // namespace

py::dict read_csv_columns(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot be opened");
    std::string header;
    if (!std::getline(in, header)) throw std::runtime_error(path + ": empty (expected a header line)");
    std::vector<std::string> names;
    for (Field& f : split(header)) names.push_back(std::move(f.text));
    std::vector<std::vector<std::string>> text(names.size());
    std::vector<bool> quoted(names.size(), false);  // a column with a quoted field is text
    std::size_t line_number = 1;
    for (std::string line; std::getline(in, line);) {
        ++line_number;
        if (line.empty()) continue;
        std::vector<Field> fields = split(line);
        if (fields.size() != names.size())
            throw std::runtime_error(path + ":" + std::to_string(line_number) + ": expected " + std::to_string(names.size()) +
                                     " fields, got " + std::to_string(fields.size()));
        for (std::size_t c = 0; c < fields.size(); ++c) {
            quoted[c] = quoted[c] || fields[c].quoted;
            text[c].push_back(std::move(fields[c].text));
        }
    }
    py::dict columns;
    for (std::size_t c = 0; c < names.size(); ++c) {
        const std::vector<std::string>& column = text[c];
        std::vector<std::int64_t> ints(column.size());
        bool all_ints = integer_column(names[c]) && !quoted[c];
        for (std::size_t r = 0; r < column.size() && all_ints; ++r) all_ints = parse_int(column[r], ints[r]);
        if (all_ints) {
            columns[py::str(names[c])] = adopt(std::move(ints));
            continue;
        }
        std::vector<double> numbers(column.size());
        bool all_numbers = !quoted[c];
        for (std::size_t r = 0; r < column.size() && all_numbers; ++r) all_numbers = parse_double(column[r], numbers[r]);
        if (all_numbers) {
            columns[py::str(names[c])] = adopt(std::move(numbers));
            continue;
        }
        columns[py::str(names[c])] = py::module_::import("numpy").attr("array")(py::cast(column));
    }
    return columns;
}

py::dict read_impact_columns(const std::string& path, const ImpactSelection& selection, bool& truncated) {
    struct Columns {
        std::vector<double> time, x, y, z, vx_in, vy_in, vz_in, vn_in, vt_in, vx_out, vy_out, vz_out, vn_out, diameter;
        std::vector<std::int32_t> shot, triangle;
        std::vector<std::int16_t> component;
        bool diameters = false;
    } c;
    {
        // The file is read without the GIL: other Python threads go on meanwhile.
        py::gil_scoped_release release;
        ImpactLogReader reader(path);
        const auto code_of = [&](std::string_view name) {
            const auto it = std::find(selection.components.begin(), selection.components.end(), name);
            if (it == selection.components.end())
                throw std::runtime_error(path + ": an impact on '" + std::string(name) + "', which the run does not log");
            return static_cast<std::int16_t>(it - selection.components.begin());
        };
        ImpactRow row;
        while (reader.next(row)) {
            if (row.time_s < selection.t_min_s || row.time_s > selection.t_max_s) continue;
            if (selection.only && row.component != *selection.only) continue;
            c.time.push_back(row.time_s);
            c.shot.push_back(row.shot);
            c.component.push_back(code_of(row.component));
            c.triangle.push_back(row.triangle);
            c.x.push_back(row.point_m.x());
            c.y.push_back(row.point_m.y());
            c.z.push_back(row.point_m.z());
            c.vx_in.push_back(row.v_in_m_per_s.x());
            c.vy_in.push_back(row.v_in_m_per_s.y());
            c.vz_in.push_back(row.v_in_m_per_s.z());
            c.vn_in.push_back(row.vn_in_m_per_s);
            c.vt_in.push_back(row.vt_in_m_per_s);
            c.vx_out.push_back(row.v_out_m_per_s.x());
            c.vy_out.push_back(row.v_out_m_per_s.y());
            c.vz_out.push_back(row.v_out_m_per_s.z());
            c.vn_out.push_back(row.vn_out_m_per_s);
            if (reader.has_shot_diameter()) c.diameter.push_back(row.shot_diameter_m);
        }
        c.diameters = reader.has_shot_diameter();
        truncated = reader.truncated();
    }
    // The same names, in the same order, as the file's header.
    py::dict columns;
    columns["time_s"] = adopt(std::move(c.time));
    columns["shot"] = adopt(std::move(c.shot));
    columns["component"] = adopt(std::move(c.component));
    columns["triangle"] = adopt(std::move(c.triangle));
    columns["x_m"] = adopt(std::move(c.x));
    columns["y_m"] = adopt(std::move(c.y));
    columns["z_m"] = adopt(std::move(c.z));
    columns["vx_in_mps"] = adopt(std::move(c.vx_in));
    columns["vy_in_mps"] = adopt(std::move(c.vy_in));
    columns["vz_in_mps"] = adopt(std::move(c.vz_in));
    columns["vn_in_mps"] = adopt(std::move(c.vn_in));
    columns["vt_in_mps"] = adopt(std::move(c.vt_in));
    columns["vx_out_mps"] = adopt(std::move(c.vx_out));
    columns["vy_out_mps"] = adopt(std::move(c.vy_out));
    columns["vz_out_mps"] = adopt(std::move(c.vz_out));
    columns["vn_out_mps"] = adopt(std::move(c.vn_out));
    if (c.diameters) columns[py::str(std::string(kImpactCsvDiameterColumn))] = adopt(std::move(c.diameter));
    return columns;
}

}  // namespace peensim::python
