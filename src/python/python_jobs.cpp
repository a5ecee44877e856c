#include "python/python_jobs.h"

#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <chrono>
#include <exception>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app/analysis/analyze_job.h"
#include "app/check/check_job.h"
#include "app/optimise/optimise_job.h"
#include "app/run/run_job.h"
#include "app/sweep/sweep_job.h"
#include "app/sweep/sweep_plan.h"
#include "common/input_error.h"
#include "model/model.h"
#include "python/python_stream.h"
#include "scene/scene_parser.h"

namespace py = pybind11;

namespace peensim::python {

namespace {

using Clock = std::chrono::steady_clock;

// How often a job looks at Python's signals (it takes the GIL to): Ctrl-C is answered within this.
constexpr auto kSignalPollInterval = std::chrono::milliseconds(50);

py::object sys_stream(const char* name) { return py::module_::import("sys").attr(name); }

// A job's stop test: Python's pending signals (KeyboardInterrupt, or whatever a handler raises),
// looked at every kSignalPollInterval, and a stop the progress callback asked for. The exception
// is kept and raised once the job has stopped cleanly (checkpointed).
class PythonStop {
public:
    bool operator()() {
        if (stop_) return true;
        const auto now = Clock::now();
        if (now < next_poll_) return false;
        next_poll_ = now + kSignalPollInterval;
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) fail(std::make_exception_ptr(py::error_already_set()));
        return stop_;
    }
    void request() { stop_ = true; }
    void fail(std::exception_ptr error) {
        if (!error_) error_ = std::move(error);
        stop_ = true;
    }
    // With the GIL: raises the kept exception, if any.
    void raise_pending() const {
        if (error_) std::rethrow_exception(error_);
    }

private:
    Clock::time_point next_poll_{};
    bool stop_ = false;
    std::exception_ptr error_;
};

py::tuple check(const std::string& path, const std::optional<std::string>& text, const std::vector<std::string>& overrides, bool strict,
                const std::string& picture) {
    std::ostringstream report;
    std::size_t warnings = 0;
    {
        PythonStream err(sys_stream("stderr"));
        py::gil_scoped_release release;
        warnings = check_scene(path, text, overrides, strict, report, err, picture);
    }
    return py::make_tuple(warnings, report.str());
}

std::string resolved_yaml(const std::string& path, const std::optional<std::string>& text, const std::vector<std::string>& overrides) {
    py::gil_scoped_release release;
    return compile_model(parse_scene(path, text, overrides))->resolved_scene_yaml;
}

std::string output_directory(const std::string& path, const std::optional<std::string>& text, const std::vector<std::string>& overrides,
                             const std::string& output_dir) {
    RunOptions o;
    o.scene_path = path;
    o.output_dir = output_dir;
    return run_output_directory(o, parse_scene(path, text, overrides));
}

std::vector<std::string> logged_components(const std::string& scene_path) {
    const SceneDescription scene = parse_scene_file(scene_path);
    std::vector<std::string> names;
    for (const ComponentDesc& c : scene.components)
        if (is_logged(scene, c)) names.push_back(c.name);
    return names;
}

int run(const std::string& path, const std::optional<std::string>& text, const std::vector<std::string>& overrides,
        const std::string& output_dir, bool resume, bool strict, bool analyze, std::optional<bool> render, bool verbose,
        const py::object& progress, int replicas, const std::string& geometry_cache) {
    PythonStop stop;
    RunOptions o;
    o.scene_path = path;
    o.scene_text = text;
    o.overrides = overrides;
    o.output_dir = output_dir;
    o.progress = false;  // the terminal's bar: a notebook has the callback instead
    o.resume = resume;
    o.strict = strict;
    o.analyze = analyze;
    o.render = render;
    if (replicas < 1) throw py::value_error("replicas: expected 1 or more, got " + std::to_string(replicas));
    o.replicas = replicas;
    o.geometry_cache_dir = geometry_cache;
    o.stop_requested = [&stop] { return stop(); };
    if (!progress.is_none()) {
        o.on_progress = [&](const RunProgress& p) {
            py::gil_scoped_acquire gil;
            try {
                // Only an explicit False stops: a callback that returns nothing lets the run go on.
                if (progress(p).is(py::bool_(false))) stop.request();
            } catch (py::error_already_set&) {
                stop.fail(std::current_exception());
            }
        };
    }
    int code = 0;
    {
        PythonStream out(verbose ? sys_stream("stdout") : py::none());
        PythonStream err(sys_stream("stderr"));
        {
            py::gil_scoped_release release;
            code = run_scene(o, out, err);
        }
    }
    stop.raise_pending();
    return code;
}

void analyze(const std::string& dir, bool verbose, double from_s, std::optional<double> to_s, double min_speed,
             std::optional<double> target, const std::string& smoothing_radius, const std::string& geometry_cache) {
    PythonStream out(verbose ? sys_stream("stdout") : py::none());
    PythonStream err(sys_stream("stderr"));
    py::gil_scoped_release release;
    AnalyzeOptions o{from_s, to_s, min_speed, target, smoothing_radius};
    o.geometry_cache_dir = geometry_cache;
    analyze_run(dir, out, err, o);
}

// sweep(seeds=...) as --seeds: None not given, a whole number checked by the sweep (0 is refused
// there, as on the command line); anything else, or a number beyond 64 bits, refused here with
// the same message.
std::optional<long long> sweep_seeds(const py::object& seeds) {
    if (seeds.is_none()) return std::nullopt;
    if (py::isinstance<py::int_>(seeds) && !py::isinstance<py::bool_>(seeds)) {
        int overflow = 0;
        const long long n = PyLong_AsLongLongAndOverflow(seeds.ptr(), &overflow);
        if (overflow == 0) return n;
    }
    throw InputError({"--seeds"}, "", sweep_seeds_problem(py::str(py::repr(seeds))));
}

// A job that can take long, as Python calls it: its messages to sys.stdout (if verbose) and
// sys.stderr line by line, the GIL released while it works, Ctrl-C passed to it as a stop request
// and raised once it has stopped.
template <class Job>
int run_from_python(bool verbose, Job&& job) {
    PythonStop stop;
    int code = 0;
    {
        PythonStream out(verbose ? sys_stream("stdout") : py::none());
        PythonStream err(sys_stream("stderr"));
        {
            py::gil_scoped_release release;
            code = job([&stop] { return stop(); }, out, err);
        }
    }
    stop.raise_pending();
    return code;
}

int sweep(const std::string& scene_path, const std::string& output_dir, const std::vector<std::string>& vary,
          const std::vector<std::string>& overrides, const py::object& seeds, int jobs, const std::string& baseline,
          const std::string& executable, bool verbose) {
    SweepOptions o;
    o.scene_path = scene_path;
    o.output_dir = output_dir;
    o.vary = vary;
    o.overrides = overrides;
    o.seeds = sweep_seeds(seeds);
    o.jobs = jobs;
    o.baseline = baseline;
    o.executable = executable;
    return run_from_python(verbose, [&](std::function<bool()> stop, std::ostream& out, std::ostream& err) {
        o.stop_requested = std::move(stop);
        return run_sweep(o, out, err);
    });
}

int optimise(const std::string& study_path, const std::string& output_dir, std::optional<int> runs, int jobs, const std::string& executable,
             bool verbose) {
    OptimiseOptions o;
    o.study_path = study_path;
    o.output_dir = output_dir;
    o.runs = runs;
    o.jobs = jobs;
    o.executable = executable;
    return run_from_python(verbose, [&](std::function<bool()> stop, std::ostream& out, std::ostream& err) {
        o.stop_requested = std::move(stop);
        return run_optimise(o, out, err);
    });
}

}  // namespace

void bind_jobs(py::module_& m) {
    py::class_<RunProgress>(m, "RunProgress", "Where a run is: passed to the progress callback of peensim.run.")
        .def_readonly("time_s", &RunProgress::time_s, "simulated time reached (s)")
        .def_readonly("duration_s", &RunProgress::duration_s, "the scene's process.duration (s)")
        .def_readonly("impacts", &RunProgress::impacts, "impacts logged so far")
        .def_readonly("wall_s", &RunProgress::wall_s, "wall time of the run so far (s)")
        .def_property_readonly(
            "fraction", [](const RunProgress& p) { return p.duration_s > 0.0 ? p.time_s / p.duration_s : 1.0; }, "time_s / duration_s")
        .def_property_readonly(
            "eta_s",
            [](const RunProgress& p) -> std::optional<double> {
                if (p.time_s <= 0.0 || p.duration_s <= 0.0) return std::nullopt;
                return p.wall_s * (p.duration_s - p.time_s) / p.time_s;
            },
            "wall time still to go at the pace so far (s), None before the run has moved")
        .def("__repr__", [](const RunProgress& p) {
            std::ostringstream s;
            s << "RunProgress(time_s=" << p.time_s << ", duration_s=" << p.duration_s << ", impacts=" << p.impacts
              << ", wall_s=" << p.wall_s << ")";
            return s.str();
        });
    m.def("check", &check, py::arg("path"), py::arg("text"), py::arg("overrides"), py::arg("strict"), py::arg("picture"),
          "Checks a scene as `peensim check` does: (warnings, report text); warnings go to sys.stderr.");
    m.def("resolved_yaml", &resolved_yaml, py::arg("path"), py::arg("text"), py::arg("overrides"),
          "The resolved scene (every default filled in, SI units, absolute paths) as YAML text.");
    m.def("output_directory", &output_directory, py::arg("path"), py::arg("text"), py::arg("overrides"), py::arg("output_dir"),
          "Where a run of the scene writes.");
    m.def("logged_components", &logged_components, py::arg("scene_path"), "The components a scene's run logs, in the scene's order.");
    m.def("run", &run, py::arg("path"), py::arg("text"), py::arg("overrides"), py::arg("output_dir"), py::arg("resume"), py::arg("strict"),
          py::arg("analyze"), py::arg("render"), py::arg("verbose"), py::arg("progress"), py::arg("replicas") = 1,
          py::arg("geometry_cache") = "", "Runs a scene as `peensim run` does; returns its exit code (0, 3 strict failure, 130 stopped).");
    m.def("analyze", &analyze, py::arg("dir"), py::arg("verbose"), py::arg("from_s"), py::arg("to_s"), py::arg("min_speed"),
          py::arg("target"), py::arg("smoothing_radius"), py::arg("geometry_cache") = "",
          "Analyses a run directory as `peensim analyze` does.");
    m.def("sweep", &sweep, py::arg("scene_path"), py::arg("output_dir"), py::arg("vary"), py::arg("overrides"), py::arg("seeds"),
          py::arg("jobs"), py::arg("baseline"), py::arg("executable"), py::arg("verbose"),
          "Runs a sweep as `peensim sweep` does; returns its exit code (0, 1 a run failed, 130 stopped).");
    m.def("optimise", &optimise, py::arg("study_path"), py::arg("output_dir"), py::arg("runs"), py::arg("jobs"), py::arg("executable"),
          py::arg("verbose"), "Runs an optimisation as `peensim optimise` does; returns its exit code (0, 1 a run failed, 130 stopped).");
}

}  // namespace peensim::python
