// A run's tables as NumPy arrays, one array per column in a dict (pandas.DataFrame(dict) takes it
// as is). Each column is parsed once into a buffer that the array then owns: no copy is made
// between the parser and NumPy.
#pragma once

#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <vector>

namespace peensim::python {

// Any CSV the analysis writes (a header line, then rows): counts and indices (triangle, facet,
// impacts, triangles, count, runs_finished, shot) become int64, other numbers float64 (an empty
// field is NaN), any other column (or one with a quoted field: a sweep's values) an array of str.
// Quoted fields follow RFC 4180.
// Throws std::runtime_error naming the file and line of a row with the wrong number of fields.
pybind11::dict read_csv_columns(const std::string& path);

// What to read of an impact log.
struct ImpactSelection {
    std::vector<std::string> components;  // logged components, in the run's order: `component` codes index it
    std::optional<std::string> only;      // just this component's rows
    double t_min_s = -1.0;                // s, rows with time_s >= this
    double t_max_s = 1e300;               // s, and <= this
};

// impacts.csv (or a killed run's impacts.csv.partial, its cut last line dropped) as columns named
// as the file's, `component` as int16 codes into selection.components. Streams the file (1 MiB
// buffer) without the GIL; memory is the arrays'. `truncated`: a cut last line was dropped.
pybind11::dict read_impact_columns(const std::string& path, const ImpactSelection& selection, bool& truncated);

}  // namespace peensim::python
