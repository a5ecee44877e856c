// peensim._native: the C++ side of the `peensim` Python package (src/python/peensim/__init__.py
// is the API users see). Binds the jobs, the scene <-> dict conversion, the tables as NumPy
// arrays, and the one error type of bad input.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "common/input_error.h"
#include "python/column_arrays.h"
#include "python/python_jobs.h"
#include "python/python_yaml.h"

namespace py = pybind11;

PYBIND11_MODULE(_native, m) {
    using namespace peensim;
    using namespace peensim::python;
    m.doc() = "the C++ side of peensim (use the peensim package)";

    // InputError(ValueError) carries where the problem is, as the command line's messages do.
    // Never destroyed: a static Python object would be released after the interpreter is gone.
    static const auto* input_error_type = new py::exception<InputError>(m, "InputError", PyExc_ValueError);
    py::register_exception_translator([](std::exception_ptr p) {
        const py::object type = py::reinterpret_borrow<py::object>(input_error_type->ptr());
        try {
            if (p) std::rethrow_exception(p);
        } catch (const InputError& e) {
            py::object error = type(e.what());
            error.attr("file") = e.where().file;
            error.attr("line") = e.where().line > 0 ? py::object(py::int_(e.where().line)) : py::object(py::none());
            error.attr("column") = e.where().column > 0 ? py::object(py::int_(e.where().column)) : py::object(py::none());
            error.attr("field") = e.field();
            error.attr("problem") = e.problem();
            PyErr_SetObject(type.ptr(), error.ptr());
        }
    });

    m.def(
        "to_yaml", [](const py::handle& v, const std::string& name) { return to_yaml(v, name); }, py::arg("value"), py::arg("name"),
        "A dict (a scene, named `name` in messages) as YAML text.");
    m.def("from_yaml", &from_yaml, py::arg("text"), py::arg("name"), "YAML text as a dict (str, int, float, bool, None, lists).");
    m.def(
        "override_value",
        [](const py::handle& v, const std::string& field, const std::string& file) { return override_value(v, field, file); },
        py::arg("value"), py::arg("field"), py::arg("file") = "<--set>", "A value as --set reads it (errors name `file` and `field`).");

    m.def("read_csv", &read_csv_columns, py::arg("path"), "A CSV of the analysis as a dict of NumPy arrays, one per column.");
    m.def(
        "read_impacts",
        [](const std::string& path, const std::vector<std::string>& components, const std::optional<std::string>& only, double t_min,
           double t_max) {
            bool truncated = false;
            py::dict columns = read_impact_columns(path, ImpactSelection{components, only, t_min, t_max}, truncated);
            return py::make_tuple(columns, truncated);
        },
        py::arg("path"), py::arg("components"), py::arg("only"), py::arg("t_min"), py::arg("t_max"),
        "An impact log as (dict of NumPy arrays, truncated).");

    bind_jobs(m);

    m.attr("executable") = PEENSIM_EXECUTABLE;
    m.attr("render_module") = PEENSIM_RENDER_MODULE;
    m.attr("cad_module") = PEENSIM_CAD_MODULE;  // "" in a build without OpenCASCADE
    m.attr("version") = PEENSIM_VERSION;
}
