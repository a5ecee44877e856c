"""peensim from Python: scenes, runs, their results as NumPy arrays, the analysis and sweeps.

    import peensim
    scene = peensim.Scene("scenes/rotating-gear.yaml").set("process.duration", "1 s")
    scene.check()                                   # raises peensim.InputError(file, line, field)
    run = peensim.run(scene, "out/py-gear", progress=peensim.print_progress)
    hits = run.impacts("gear")                      # {"time_s": array, "vn_in_mps": array, ...}
    study = peensim.sweep(scene, "out/rpm", vary={"components[gear].motion.speed": ["15 rpm", "60 rpm"]}, seeds=2)
    study.comparison["time_to_target_everywhere_s"]

Every job is the command line's own (`peensim run`, `analyze`, `check`, `sweep`): the same outputs in
the same run directories, byte for byte. Units are SI, and every column name carries its unit.
"""

import json
import os
import warnings

from . import _native

__all__ = ["Scene", "CheckReport", "Run", "Sweep", "Optimisation", "InputError", "HealthError", "RunProgress",
           "run", "analyze", "sweep", "optimise", "print_progress"]
__version__ = _native.version

# A scene's bad input: a ValueError with .file, .line, .column (None when unknown), .field, .problem.
InputError = _native.InputError
# What a progress callback receives: time_s, duration_s, fraction, impacts, wall_s, eta_s.
RunProgress = _native.RunProgress

# Pictures (render: a scene's animation, Scene.check(picture=...)) come from this build's module,
# and STEP and IGES parts too (a build without OpenCASCADE has none and says what to install). Set
# only while the build's file is there (a module path that is set is the only one peensim tries),
# and unless the user set one: empty counts as unset, as for the command line.
for _variable, _module in (("PEENSIM_RENDER_MODULE", _native.render_module), ("PEENSIM_CAD_MODULE", _native.cad_module)):
    if _module and os.path.isfile(_module) and not os.environ.get(_variable):
        os.environ[_variable] = _module
del _variable, _module

_STOPPED = 130  # the jobs' exit code of a run stopped at a checkpoint


class HealthError(RuntimeError):
    """A run with strict=True had numerical trouble (a lost shot, a deep penetration...): see its run.summary."""

    def __init__(self, message, run):
        super().__init__(message)
        self.run = run


class CheckReport:
    """What Scene.check found: the number of warnings (printed to sys.stderr as found) and the report
    `peensim check` prints (the assembly, the placed shot, the resolved scene)."""

    def __init__(self, warnings, text):
        self.warnings = warnings
        self.text = text

    def __repr__(self):
        return f"CheckReport(warnings={self.warnings})"

    def __str__(self):
        return self.text


class Scene:
    """A scene: a scene file, or a dict (as a scene file's YAML would read), and overrides applied to
    it in order, as `--set path=value` is on the command line.

    Scene("scenes/gear.yaml")                             a file
    Scene("scenes/gear.yaml", set={"shot.count": 200})   with overrides
    Scene.from_dict({...}, base_dir="scenes")            a dict; relative mesh paths from base_dir
    """

    def __init__(self, path, set=None):
        self._path = os.fspath(path)
        self._text = None
        self._overrides = []
        if set:
            self.set(set)

    @classmethod
    def from_dict(cls, scene, base_dir=".", name="scene"):
        """A scene from a dict. Values keep their units as text ("2 mm", "30 rpm"); plain numbers are SI.
        Messages name it `<base_dir>/<name>` with lines of `scene.yaml_text`; a run without an output
        directory writes to out/<name>."""
        text = _native.to_yaml(scene, os.path.join(os.path.abspath(os.fspath(base_dir)), name))
        return cls.from_yaml(text, base_dir=base_dir, name=name)

    @classmethod
    def from_yaml(cls, text, base_dir=".", name="scene"):
        """A scene from YAML text (named and placed as from_dict's)."""
        self = cls.__new__(cls)
        self._path = os.path.join(os.path.abspath(os.fspath(base_dir)), name)
        self._text = text
        self._overrides = []
        return self

    @property
    def path(self):
        """The scene file (for a dict: the name its messages use)."""
        return self._path

    @property
    def yaml_text(self):
        """The YAML the scene is read from (a file's text, or the dict's)."""
        if self._text is not None:
            return self._text
        with open(self._path, encoding="utf-8") as f:
            return f.read()

    @property
    def in_memory(self):
        return self._text is not None

    @property
    def overrides(self):
        """The overrides as `--set` strings, in the order they apply."""
        return list(self._overrides)

    def set(self, path, value=None):
        """Overrides a field as `--set path=value` does: set("shot.diameter", "1 mm"), or several at once
        with a dict. Values: text as written in a scene file ("60 rpm"), numbers (SI), lists, dicts.
        Returns the scene, so calls chain. Nothing is checked until check(), run() or resolved()."""
        if isinstance(path, dict):
            for key, v in path.items():
                self.set(key, v)
            return self
        if value is None:
            if "=" not in path:
                raise ValueError(f"set({path!r}): expected set(path, value) or set('path=value')")
            self._overrides.append(path)
        else:
            self._overrides.append(f"{path}={_native.override_value(value, path)}")
        return self

    def copy(self):
        """An independent copy (its overrides a list of its own)."""
        other = Scene.__new__(Scene)
        other._path, other._text, other._overrides = self._path, self._text, list(self._overrides)
        return other

    def check(self, strict=False, picture=None):
        """Checks everything a run would (scene, meshes, plausibility, enclosure, assembly, shot
        placement) as `peensim check` does. Raises InputError with file, line and field; warnings are
        printed to sys.stderr (strict=True makes them errors). picture: also draw the assembly to this PNG."""
        count, text = _native.check(self._path, self._text, self._overrides, strict, os.fspath(picture) if picture else "")
        return CheckReport(count, text)

    def to_dict(self):
        """The scene as written (its file or dict), without the overrides: edit it and make a new
        Scene.from_dict(d, base_dir=...) (relative mesh paths are read from base_dir)."""
        return _native.from_yaml(self.yaml_text, self._path)

    def resolved_yaml(self):
        """The resolved scene: every default filled in, SI units, absolute paths, overrides applied."""
        return _native.resolved_yaml(self._path, self._text, self._overrides)

    def resolved(self):
        """resolved_yaml() as a dict."""
        return _native.from_yaml(self.resolved_yaml(), self._path)

    def __repr__(self):
        source = f"dict {self._path!r}" if self.in_memory else repr(self._path)
        return f"Scene({source}, overrides={self._overrides!r})"


def _as_scene(scene):
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, dict):
        return Scene.from_dict(scene)
    return Scene(scene)


def _read_text(path):
    """A file's text; None when there is no such file."""
    if not os.path.isfile(path):
        return None
    with open(path, encoding="utf-8") as f:
        return f.read()


def _write_if_changed(path, text):
    """Writes `text` to `path` (whole, by rename) unless it holds it already: a resumed job finds
    its file unchanged, mtime and all."""
    if _read_text(path) != text:
        with open(path + ".tmp", "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(path + ".tmp", path)


def _json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


class Run:
    """A run directory, finished or not: Run("out/gear"). What peensim.run returns."""

    def __init__(self, directory):
        self.dir = os.fspath(directory)
        self._scene_file = os.path.join(self.dir, "scene.resolved.yaml")
        if not os.path.isfile(self._scene_file):
            raise FileNotFoundError(f"{self.dir}: not a peensim run directory (no scene.resolved.yaml)")
        self._components = None

    def __repr__(self):
        return f"Run({self.dir!r}, finished={self.finished})"

    @property
    def finished(self):
        """Whether the run reached its duration (impacts.csv is written only then)."""
        return os.path.isfile(os.path.join(self.dir, "impacts.csv"))

    @property
    def scene(self):
        """The run's resolved scene, as a Scene."""
        return Scene(self._scene_file)

    @property
    def components(self):
        """The logged components, in the scene's order: the impacts' `component` codes index this list."""
        if self._components is None:
            self._components = _native.logged_components(self._scene_file)
        return list(self._components)

    @property
    def summary(self):
        """summary.json as a dict (docs/user-guide.md, "Outputs"); None before the run wrote one."""
        path = os.path.join(self.dir, "summary.json")
        return _json(path) if os.path.isfile(path) else None

    def impacts(self, component=None, t_min=None, t_max=None):
        """The impact log as a dict of NumPy arrays, one per impacts.csv column (same names and
        units; `component` as int16 codes into run.components), read once into the arrays, no copy
        after: pandas.DataFrame(run.impacts()) takes it as is. component: only that one's impacts;
        t_min, t_max (s): only impacts in that window. A run that did not finish gives its partial log."""
        log = os.path.join(self.dir, "impacts.csv")
        if not os.path.isfile(log):
            log = os.path.join(self.dir, "impacts.csv.partial")
        if not os.path.isfile(log):
            raise FileNotFoundError(f"{self.dir}: no impact log (impacts.csv or impacts.csv.partial)")
        if component is not None and component not in self.components:
            raise ValueError(f"{component!r} is not logged by this run; expected one of {self.components}")
        columns, truncated = _native.read_impacts(log, self.components, component,
                                                  -1.0 if t_min is None else float(t_min),
                                                  1e300 if t_max is None else float(t_max))
        if truncated:
            warnings.warn(f"{log}: the log ends inside a row (a killed run); that row is left out", RuntimeWarning, stacklevel=2)
        return columns

    def _component(self, component):
        names = self.components
        if component is None:
            if len(names) != 1:
                raise ValueError(f"the run logs {names}: name the component")
            return names[0]
        if component not in names:
            raise ValueError(f"{component!r} is not logged by this run; expected one of {names}")
        return component

    def _analysis_file(self, name):
        path = os.path.join(self.dir, "analysis", name)
        if not os.path.isfile(path):
            raise FileNotFoundError(f"{path}: not written; analyse the run first (run.analyze())")
        return path

    def triangles(self, component=None):
        """Per-triangle fields of a logged component (analysis/<component>_triangles.csv) as a dict of
        NumPy arrays: triangle, facet, area_mm2, impacts, impacts_per_mm2_s, mean_vn_mps (NaN without
        impacts), max_vn_mps, energy_J_per_m2, coverage."""
        return _native.read_csv(self._analysis_file(f"{self._component(component)}_triangles.csv"))

    def regions(self, component=None):
        """Per-region figures (analysis/<component>_regions.csv) as a dict of arrays (region names as str)."""
        return _native.read_csv(self._analysis_file(f"{self._component(component)}_regions.csv"))

    def coverage(self, component=None):
        """Coverage against time (analysis/<component>_coverage.csv): time_s, coverage (fraction)."""
        return _native.read_csv(self._analysis_file(f"{self._component(component)}_coverage.csv"))

    def histograms(self, component=None):
        """Normal speed, impact angle and dent diameter histograms (analysis/<component>_histograms.csv)."""
        return _native.read_csv(self._analysis_file(f"{self._component(component)}_histograms.csv"))

    @property
    def figures(self):
        """analysis/figures.json as a dict: per component its impacts, rate, speeds, coverage and the
        time to the target coverage (whole part, everywhere, per region) with its interval."""
        return _json(self._analysis_file("figures.json"))

    @property
    def report(self):
        """analysis/report.md as text."""
        with open(self._analysis_file("report.md"), encoding="utf-8") as f:
            return f.read()

    @property
    def report_html(self):
        """The path of analysis/report.html: the report with its pictures and each part in 3D (turn it,
        colour it by coverage, impact density, mean normal speed, its region's time to the target or
        region, click to read them), one file that opens offline: webbrowser.open(run.report_html)."""
        return self._analysis_file("report.html")

    def analyze(self, verbose=False, *, from_s=0.0, to_s=None, min_speed=0.0, target=None, smoothing_radius=None,
                geometry_cache=None):
        """Analyses the run (as `peensim analyze`): writes analysis/. Returns the run.
        from_s, to_s (s): analyse only the impacts in this window (drop a start-up transient);
        min_speed (m/s): leave out slower impacts; target: the coverage the report measures against
        (a fraction; None: the run's process.until_coverage, else 0.98);
        smoothing_radius: the maps' radius, in m or as text with a unit ("1.5 mm"); None: the
        scene's output.smoothing_radius, else the analysis' choice; geometry_cache: a folder of
        the parts' coverage geometry to reuse and keep (`--geometry-cache`)."""
        if smoothing_radius is None:
            radius = ""
        elif isinstance(smoothing_radius, str):
            radius = smoothing_radius
        else:
            radius = repr(float(smoothing_radius)) + " m"
        _native.analyze(self.dir, verbose, float(from_s), None if to_s is None else float(to_s), float(min_speed),
                        None if target is None else float(target), radius,
                        os.fspath(geometry_cache) if geometry_cache else "")
        return self


def run(scene, output_dir=None, *, progress=None, resume=False, strict=False, analyze=True, render=None,
        scheme=None, verbose=False, replicas=1, geometry_cache=None):
    """Runs a scene as `peensim run` does and returns its Run.

    scene: a Scene, a scene file's path, or a dict. output_dir: the run directory (default: the
    scene's output.directory, else out/<scene name>). progress: called with a RunProgress about
    four times a second and at the end; returning False stops the run at its next checkpoint
    (run.finished is then False; resume=True continues it). Ctrl-C (KeyboardInterrupt) stops it
    the same way and is raised once the checkpoint is written; so is an exception the callback
    raises. strict: warnings are errors, and numerical trouble raises HealthError. analyze: write
    analysis/ when it finishes. render: True/False records or not the animation (None: as the
    scene says). scheme: "event", "step" or "soft". verbose: print the summary as the command does.
    replicas: the run as that many replicas of the chamber on as many cores (`--replicas`).
    geometry_cache: a folder of the parts' coverage geometry to reuse and keep, shared by runs of
    one assembly and shot (`--geometry-cache`).
    """
    scene = _as_scene(scene)
    overrides = scene.overrides + ([f"accuracy.scheme={scheme}"] if scheme else [])
    directory = _native.output_directory(scene._path, scene._text, overrides, os.fspath(output_dir) if output_dir else "")
    code = _native.run(scene._path, scene._text, overrides, directory, resume, strict, analyze, render, verbose, progress, replicas,
                       os.fspath(geometry_cache) if geometry_cache else "")
    result = Run(directory)
    if code == 3:
        raise HealthError(f"{directory}: the run had numerical trouble: {result.summary['health_counters']}", result)
    if code == _STOPPED and progress is None:
        raise KeyboardInterrupt(f"{directory}: the run stopped at a checkpoint; run it again with resume=True")
    return result


def analyze(directory, verbose=False, **window):
    """Analyses a run directory (as `peensim analyze`); returns its Run. window: from_s, to_s,
    min_speed, target, smoothing_radius, as Run.analyze takes them."""
    return Run(directory).analyze(verbose, **window)


def print_progress(p):
    """A progress callback that prints one line in place: simulated time, %, impacts, time to go."""
    eta = "" if p.eta_s is None else f", {p.eta_s:.0f} s to go"
    end = "\n" if p.time_s >= p.duration_s else ""
    print(f"\r{p.time_s:.4g}/{p.duration_s:.4g} s ({100 * p.fraction:.0f} %), {p.impacts} impacts{eta}   ", end=end, flush=True)


class Sweep:
    """A sweep directory: every run of every variant, and the comparison (sweep/comparison.csv)."""

    def __init__(self, directory):
        self.dir = os.fspath(directory)
        if not os.path.isdir(os.path.join(self.dir, "sweep")):
            raise FileNotFoundError(f"{self.dir}: not a peensim sweep directory (no sweep/)")

    def __repr__(self):
        return f"Sweep({self.dir!r}, runs={len(self.runs)})"

    @property
    def comparison(self):
        """sweep/comparison.csv as a dict of NumPy arrays: a row per variant (docs/user-guide.md, "What-if sweeps")."""
        return _native.read_csv(os.path.join(self.dir, "sweep", "comparison.csv"))

    @property
    def report(self):
        """sweep/report.md as text."""
        with open(os.path.join(self.dir, "sweep", "report.md"), encoding="utf-8") as f:
            return f.read()

    @property
    def report_html(self):
        """The path of sweep/report.html: the comparison with its plots and the variants side by side
        in one 3D view, one file that opens offline: webbrowser.open(study.report_html)."""
        return os.path.join(self.dir, "sweep", "report.html")

    @property
    def runs(self):
        """{variant name: [Run of seed replicate 0, 1, ...]} for every run directory of the sweep, in
        the sweep's order (the comparison's rows) once it has been compared."""
        found = {}
        for variant in os.listdir(self.dir):
            vdir = os.path.join(self.dir, variant)
            if variant == "sweep" or not os.path.isdir(vdir):
                continue
            seeds = sorted((d for d in os.listdir(vdir) if d[:1] == "s" and d[1:].isdigit()), key=lambda d: int(d[1:]))
            runs = [Run(os.path.join(vdir, d)) for d in seeds if os.path.isfile(os.path.join(vdir, d, "scene.resolved.yaml"))]
            if runs:
                found[variant] = runs
        compared = os.path.join(self.dir, "sweep", "comparison.csv")
        order = self.comparison["variant"].tolist() if os.path.isfile(compared) else []
        rank = {name: k for k, name in enumerate(order)}
        return dict(sorted(found.items(), key=lambda item: (rank.get(item[0], len(rank)), item[0])))


def _vary_spec(path, values):
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise ValueError(f"vary[{path!r}]: expected a list of values, got {values!r}")
    return f"{path}=" + ",".join(_native.override_value(v, path, "--vary") for v in values)


def sweep(scene, output_dir, vary=None, *, seeds=None, jobs=0, set=None, baseline=None, verbose=True):
    """Runs every variant of a scene as `peensim sweep` does (each an ordinary run, several at once on
    the local cores) and compares them; returns the Sweep.

    vary: {path: [values]}, every combination is a variant (or a sweep file as `scene`, which gives
    its own). seeds: replicates per variant (process.seed, +1, ...; default the sweep file's, else 1). jobs: runs at once (0: every
    core). set: overrides for every run ({path: value} or ["path=value"]). baseline: the variant the
    others are compared with (default the first). Resumable: the same call skips finished runs.
    Ctrl-C stops the runs at their checkpoints and raises KeyboardInterrupt. A run that fails twice
    is reported with a RuntimeWarning; the others are compared.
    """
    overrides = []
    if isinstance(set, dict):
        overrides = [f"{k}={_native.override_value(v, k)}" for k, v in set.items()]
    elif set:
        overrides = list(set)
    output_dir = os.fspath(output_dir)
    if isinstance(scene, Scene) and scene.in_memory:
        # The runs are processes that read a file: the resolved scene (absolute mesh paths) is it.
        os.makedirs(os.path.join(output_dir, "sweep"), exist_ok=True)
        scene_path = os.path.join(output_dir, "sweep", "scene.yaml")
        _write_if_changed(scene_path, scene.resolved_yaml())
    else:
        scene = _as_scene(scene)
        scene_path = scene._path
        overrides = scene.overrides + overrides
    specs = [_vary_spec(p, v) for p, v in (vary or {}).items()]
    executable = os.environ.get("PEENSIM_EXECUTABLE", _native.executable)
    code = _native.sweep(scene_path, output_dir, specs, overrides, seeds, jobs, baseline or "", executable, verbose)
    if code == _STOPPED:
        raise KeyboardInterrupt(f"{output_dir}: the sweep stopped; its runs checkpointed: the same call goes on")
    if code != 0:
        warnings.warn(f"{output_dir}: some runs failed (see {output_dir}/sweep/logs/); the others are compared",
                      RuntimeWarning, stacklevel=2)
    return Sweep(output_dir)


class Optimisation:
    """An optimisation directory (`peensim optimise`): every setting's runs, the winner, the report."""

    def __init__(self, directory):
        self.dir = os.fspath(directory)
        if not os.path.isfile(os.path.join(self.dir, "optimise", "journal.json")):
            raise FileNotFoundError(f"{self.dir}: not a peensim optimisation directory (no optimise/journal.json)")

    def __repr__(self):
        return f"Optimisation({self.dir!r})"

    @property
    def winner(self):
        """optimise/winner.json as a dict: the winning setting's name, its values, its --set overrides,
        the objective predicted (mean, low, high), measured in its search runs and confirmed by new
        runs (mean, ci95), the start's confirmed value, and the change from the start, predicted and
        confirmed, with whether the prediction holds."""
        with open(os.path.join(self.dir, "optimise", "winner.json"), encoding="utf-8") as f:
            return json.load(f)

    @property
    def evaluations(self):
        """optimise/evaluations.csv as a dict of NumPy arrays: a row per setting, in the order run."""
        return _native.read_csv(os.path.join(self.dir, "optimise", "evaluations.csv"))

    @property
    def report(self):
        """optimise/report.md as text."""
        with open(os.path.join(self.dir, "optimise", "report.md"), encoding="utf-8") as f:
            return f.read()

    @property
    def report_html(self):
        """The path of optimise/report.html: the report with its plots and the start and the winner
        side by side in one 3D view, one file that opens offline."""
        return os.path.join(self.dir, "optimise", "report.html")

    def runs(self, setting):
        """[Run of replicate 0, 1, ...] of a setting ("start", "e007", "confirm-start", ...)."""
        base = os.path.join(self.dir, setting)
        found = sorted((d for d in os.listdir(base) if d.startswith("s") and d[1:].isdigit()), key=lambda d: int(d[1:])) \
            if os.path.isdir(base) else []
        return [Run(os.path.join(base, d)) for d in found]


def optimise(study, output_dir, *, runs=None, jobs=0, verbose=True):
    """Searches a study's process variables for the best setting as `peensim optimise` does
    (Bayesian optimisation over ordinary runs, several at once; resumable: the same call goes on
    where it stopped) and confirms the winner with new runs; returns the Optimisation.

    study: a study file's path, or a dict as its YAML would read ({"scene": path or Scene,
    "variables": {name: {"path": ..., "min": "15 rpm", "max": "120 rpm"}}, "objective": ...,
    "constraints": [...], "runs": 24, ...}: docs/user-guide.md, "Finding the best process"); a
    Scene's overrides join the study's `set`, and a Scene built in memory is written to
    output_dir/optimise/scene.yaml. runs: the search's budget (default the study's). jobs: runs at
    once (0: every core). Ctrl-C stops the runs at their checkpoints and raises KeyboardInterrupt.
    A run that fails twice is reported with a RuntimeWarning; the search goes on without it.
    """
    output_dir = os.fspath(output_dir)
    if isinstance(study, dict):
        study = dict(study)
        folder = os.path.join(output_dir, "optimise")
        os.makedirs(folder, exist_ok=True)
        scene = study.get("scene")
        if isinstance(scene, Scene):
            if scene.in_memory:
                scene_path = os.path.join(folder, "scene.yaml")
                _write_if_changed(scene_path, scene.resolved_yaml())
                study["scene"] = os.path.abspath(scene_path)
            else:
                study["scene"] = os.path.abspath(scene._path)
                study["set"] = list(scene.overrides) + list(study.get("set") or [])
        elif scene is not None:
            study["scene"] = os.path.abspath(os.fspath(scene))
        # JSON is YAML: the study file the command reads, kept beside the results (errors name its lines).
        study_path = os.path.join(folder, "study.yaml")
        _write_if_changed(study_path, json.dumps(study, indent=1) + "\n")
    else:
        study_path = os.fspath(study)
    executable = os.environ.get("PEENSIM_EXECUTABLE", _native.executable)
    code = _native.optimise(study_path, output_dir, runs, jobs, executable, verbose)
    if code == _STOPPED:
        raise KeyboardInterrupt(f"{output_dir}: the optimisation stopped; its runs checkpointed: the same call goes on")
    if code != 0:
        warnings.warn(f"{output_dir}: some runs failed (see {output_dir}/optimise/logs/); the search went on without them",
                      RuntimeWarning, stacklevel=2)
    return Optimisation(output_dir)
