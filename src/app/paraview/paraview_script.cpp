#include "app/paraview/paraview_script.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <utility>

#include "analysis/area_percentile.h"
#include "app/paraview/paraview_assembly.h"
#include "app/paraview/paraview_shot_series.h"
#include "output/atomic_file.h"
#include "output/run_directory.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// The script's code; the run's own values come before it, as RUN.
constexpr const char* kScriptBody = R"PY(
import builtins  # min and max: pvbatch's namespace may hold VTK's array versions
import math
import os
import sys
import xml.etree.ElementTree as ElementTree

from paraview import servermanager
from paraview.simple import (AnnotateTime, AssignViewToLayout, ColorBy, CreateView, ExtractBlock, GetActiveViewOrCreate,
                             GetAnimationScene, GetColorTransferFunction, GetLayout, GetScalarBar, ProgrammableFilter, PVDReader,
                             Render, SaveScreenshot, SetActiveView, Show, Text, XMLMultiBlockDataReader, XMLPolyDataReader)
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

try:
    HERE = os.path.dirname(os.path.abspath(__file__))
except NameError:  # run from ParaView's Python shell as text: the directory it was written in
    HERE = RUN["analysis_dir"]

ROLE_NAMES = ["sonotrode", "chamber", "part", "fixture", "almen"]  # the `role` cell array's codes
ROLE_COLOURS = [[0.55, 0.6, 0.7], [0.75, 0.75, 0.78], [0.85, 0.65, 0.3], [0.45, 0.35, 0.25], [0.3, 0.6, 0.35]]
CHAMBER_OPACITY = 0.25

# Poses a data set (or each block of a multiblock) at the pipeline's time from its component's
# motion (the closed form of peensim's model/kinematics.h). MOTIONS maps a block name ("" for a
# single data set) to the field data of its assembly block; FRAME is "component" (points in the
# component's frame: the analysis' files) or "world_at_0" (the assembly's files).
POSE_FILTER = r"""
import math
import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet, vtkDataObject
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp

MOTIONS = %(motions)r
FRAME = %(frame)r

def rotation(axis, angle):
    u = np.asarray(axis, dtype=float)
    u = u / np.linalg.norm(u)
    k = np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])
    return np.eye(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * (k @ k)

def pose(m, t):
    r = np.array(m["pose_rotation"], dtype=float).reshape(3, 3)
    p = np.array(m["pose_translation_m"], dtype=float)
    if m["motion"] == "vibrating":
        phase = 2.0 * math.pi * m["frequency_hz"][0] * t + m["phase_rad"][0]
        p = p + np.array(m["vibration_axis"]) * m["amplitude_m"][0] * math.sin(phase)
    elif m["motion"] == "rotating":
        spin = rotation(m["axis_direction"], m["angular_speed_rad_per_s"][0] * t)
        centre = np.array(m["axis_point_m"], dtype=float)
        r, p = spin @ r, centre + spin @ (p - centre)
    return r, p

def posed(data, m, t):
    out = data.NewInstance()
    out.ShallowCopy(data)
    if m is None or data.GetNumberOfPoints() == 0:
        return out
    x = dsa.WrapDataObject(data).Points
    r, p = pose(m, t)
    if FRAME == "world_at_0":  # back to the component's frame first
        r0, p0 = pose(m, 0.0)
        x = (x - p0) @ r0
    points = vtkPoints()
    points.SetData(dsa.numpyTovtkDataArray(np.ascontiguousarray(x @ r.T + p), "Points"))
    out.SetPoints(points)
    return out

info = self.GetOutputInformation(0)
t = info.Get(sddp.UPDATE_TIME_STEP()) if info.Has(sddp.UPDATE_TIME_STEP()) else 0.0
source = self.GetInputDataObject(0, 0)
target = self.GetOutputDataObject(0)
if source.IsA("vtkMultiBlockDataSet"):
    target.CopyStructure(source)
    for i in range(source.GetNumberOfBlocks()):
        name = source.GetMetaData(i).Get(vtkCompositeDataSet.NAME()) if source.HasMetaData(i) else ""
        block = source.GetBlock(i)
        if block is not None:
            target.SetBlock(i, posed(block, MOTIONS.get(name), t))
        target.GetMetaData(i).Set(vtkCompositeDataSet.NAME(), name)
else:
    target.ShallowCopy(posed(source, MOTIONS.get(""), t))
target.GetInformation().Set(vtkDataObject.DATA_TIME_STEP(), t)
"""

# Declares the run's time range, so that the time of a pose filter over a static input follows the
# animation (its input's own time steps, a coverage series', are kept).
POSE_INFORMATION = r"""
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp
info = self.GetOutputInformation(0)
if not info.Has(sddp.TIME_STEPS()):
    info.Set(sddp.TIME_RANGE(), [0.0, %(duration)r], 2)
"""


def path(relative):
    return os.path.normpath(os.path.join(HERE, relative))


def field_data(vtp_file):
    """A .vtp's field data as {name: text or list of numbers}."""
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(vtp_file)
    reader.Update()
    fields = reader.GetOutput().GetFieldData()
    values = {}
    for i in range(fields.GetNumberOfArrays()):
        a = fields.GetAbstractArray(i)
        if a.IsA("vtkStringArray"):
            values[a.GetName()] = a.GetValue(0)
        else:
            values[a.GetName()] = [a.GetComponent(0, c) for c in range(a.GetNumberOfComponents())]
    return values


def assembly_blocks(vtm_file):
    """[(component name, its .vtp)] of the assembly's multiblock."""
    root = ElementTree.parse(vtm_file).getroot()
    directory = os.path.dirname(vtm_file)
    return [(d.get("name"), os.path.join(directory, d.get("file"))) for d in root.iter("DataSet")]


def posed(name, source, motions, frame):
    f = ProgrammableFilter(registrationName=name, Input=source)
    f.OutputDataSetType = "Same as Input"
    f.Script = POSE_FILTER % {"motions": motions, "frame": frame}
    f.RequestInformationScript = POSE_INFORMATION % {"duration": RUN["duration_s"]}
    return f


def colour_by_role(display):
    ColorBy(display, ("CELLS", "role"))
    lut = GetColorTransferFunction("role")
    lut.InterpretValuesAsCategories = 1
    lut.Annotations = [x for code, name in enumerate(ROLE_NAMES) for x in (str(code), name)]
    lut.IndexedColors = [c for colour in ROLE_COLOURS for c in colour]


def colour_by(view, display, association, array, preset, top, title, corner):
    """Colours by an array over [0, top] (fixed: the same colours at every time), with its bar in a corner."""
    ColorBy(display, (association, array))
    lut = GetColorTransferFunction(array)
    lut.ApplyPreset(preset, True)
    lut.AutomaticRescaleRangeMode = "Never"
    lut.RescaleTransferFunction(0.0, top if top > 0.0 else 1.0)
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.RangeLabelFormat = "%-#.3g"
    bar.Orientation = "Horizontal"
    bar.WindowLocation = corner
    bar.ScalarBarLength = 0.3
    bar.TitleFontSize = 12
    bar.LabelFontSize = 11
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]


def unit(v):
    norm = math.sqrt(builtins.sum(x * x for x in v))
    return [x / norm for x in v]


def front():
    """The horizontal direction the views are seen from (-y unless up is along y)."""
    up = RUN["up"]
    side = [0.0, -1.0, 0.0] if abs(up[1]) < 0.9 else [1.0, 0.0, 0.0]
    along = builtins.sum(s * u for s, u in zip(side, up))
    return unit([s - along * u for s, u in zip(side, up)])


def look_from(view, bounds, direction):
    """Frames `bounds` seen from `direction` (from the centre towards the camera)."""
    centre = [(bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2]
    size = builtins.max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4])
    direction = unit(direction)
    up = RUN["up"]
    if abs(builtins.sum(d * u for d, u in zip(direction, up))) > 0.95:  # looking along up: the front is up on screen
        up = front()
    view.CameraFocalPoint = centre
    view.CameraPosition = [c + 2.6 * size * d for c, d in zip(centre, direction)]
    view.CameraViewUp = up
    view.CameraViewAngle = 30


def build():
    """Opens the run's ParaView files in two views side by side; returns {name: proxy} of what it opened."""
    made = {}
    process = GetActiveViewOrCreate("RenderView")
    layout = GetLayout(process)
    layout.SplitHorizontal(0, 0.5)
    results = CreateView("RenderView")
    AssignViewToLayout(view=results, layout=layout, hint=2)
    for view in (process, results):
        view.OrientationAxesVisibility = 0
        view.Background = [1.0, 1.0, 1.0]
        view.UseColorPaletteForBackground = 0

    motions = {}
    assembly_file = path(RUN["assembly"])
    parts_with_coverage = [p["name"] for p in RUN["parts"] if p["coverage_series"] and os.path.exists(path(p["coverage_series"]))]
    if os.path.exists(assembly_file):
        blocks = assembly_blocks(assembly_file)
        motions = {name: field_data(block) for name, block in blocks}
        assembly = XMLMultiBlockDataReader(registrationName="assembly", FileName=[assembly_file])
        chamber = [n for n, _ in blocks if motions[n]["role_name"] == "chamber"]
        others = [n for n, _ in blocks if motions[n]["role_name"] != "chamber" and n not in parts_with_coverage]
        for name, selected, opacity in (("chamber", chamber, CHAMBER_OPACITY), ("assembly_parts", others, 1.0)):
            if not selected:
                continue
            extract = ExtractBlock(registrationName=name + "_blocks", Input=assembly, Selectors=["/Root/" + n for n in selected])
            made[name] = posed(name, extract, motions, "world_at_0")
            SetActiveView(process)
            display = Show(made[name], process)
            colour_by_role(display)
            display.Opacity = opacity
            display.SetScalarBarVisibility(process, False)
    else:
        print("no " + assembly_file + " (a run of an earlier peensim): parts shown in their own frames")

    for part in RUN["parts"]:
        name = part["name"]
        motion = {"": motions[name]} if name in motions else {}
        if name in parts_with_coverage:
            series = PVDReader(registrationName=name + "_coverage_files", FileName=path(part["coverage_series"]))
            made[name + "_coverage"] = posed(name + "_coverage", series, motion, "component")
            SetActiveView(process)
            colour_by(process, Show(made[name + "_coverage"], process), "CELLS", "coverage", "Viridis (matplotlib)", 1.0,
                      "coverage", "Lower Right Corner")
        if os.path.exists(path(part["fields"])):
            fields = XMLPolyDataReader(registrationName=name + "_fields_file", FileName=[path(part["fields"])])
            made[name + "_fields"] = posed(name + "_fields", fields, motion, "component")
            SetActiveView(results)
            colour_by(results, Show(made[name + "_fields"], results), "CELLS", "impacts_per_mm2_s", "Viridis (matplotlib)",
                      part["impacts_per_mm2_s_scale"], "impacts per mm2 s", "Lower Left Corner")
        if os.path.exists(path(part["impacts"])):
            impacts = XMLPolyDataReader(registrationName=name + "_impacts_file", FileName=[path(part["impacts"])])
            made[name + "_impacts"] = posed(name + "_impacts", impacts, motion, "component")
            SetActiveView(results)
            display = Show(made[name + "_impacts"], results)
            display.SetRepresentationType("Points")
            display.PointSize = 3
            colour_by(results, display, "POINTS", "vn_in_mps", "Jet", RUN["speed_scale_mps"], "normal speed (m/s)",
                      "Lower Right Corner")

    shots_file = path(RUN["shots"])
    if os.path.exists(shots_file):
        made["shots"] = PVDReader(registrationName="shots", FileName=shots_file)
        SetActiveView(process)
        display = Show(made["shots"], process)
        display.SetRepresentationType("Point Gaussian")
        display.ShaderPreset = "Sphere"
        display.ScaleByArray = 1
        display.SetScaleArray = ["POINTS", "shot_diameter_m"]
        display.UseScaleFunction = 0
        display.GaussianRadius = 0.5  # times the diameter: the shot's radius
        colour_by(process, display, "POINTS", "speed_mps", "Jet", RUN["speed_scale_mps"], "shot speed (m/s)", "Lower Left Corner")

    clock = AnnotateTime(registrationName="time")
    clock.Format = "t = {time:.4f} s"
    note = Text(registrationName="note")
    note.Text = "impacts from %.4g s to %.4g s" % (RUN["window_from_s"], RUN["window_to_s"])
    for proxy, view in ((clock, process), (note, results)):
        display = Show(proxy, view)
        display.FontSize = 14
        display.Color = [0.1, 0.1, 0.1]
        display.WindowLocation = "Upper Left Corner"
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    for view, keys in ((process, list(made)), (results, [k for k in made if k.endswith("_fields") or k.endswith("_impacts")])):
        shown = [made[k] for k in keys if k != "shots"]
        if not shown:
            continue
        bounds = [1e300, -1e300] * 3
        for proxy in shown:
            b = proxy.GetDataInformation().GetBounds()
            for i in range(3):
                bounds[2 * i] = builtins.min(bounds[2 * i], b[2 * i])
                bounds[2 * i + 1] = builtins.max(bounds[2 * i + 1], b[2 * i + 1])
        f, u, hits = front(), RUN["up"], RUN["impacts_seen_from"]
        if view == process or not builtins.any(hits):
            look_from(view, bounds, [a + 0.6 * b for a, b in zip(f, u)])  # the front, from above
        else:
            look_from(view, bounds, [a + 0.8 * b for a, b in zip(hits, f)])  # where the impacts came from
    SetActiveView(process)
    return made, layout


def describe(made, time_s):
    """Prints, for each opened item at time_s: its points, first point, bounds and arrays (tests read it)."""
    for name, proxy in made.items():
        proxy.UpdatePipeline(time_s)
        data = servermanager.Fetch(proxy)
        if data.IsA("vtkMultiBlockDataSet"):
            from vtkmodules.vtkFiltersCore import vtkAppendPolyData

            append = vtkAppendPolyData()
            it = data.NewTreeIterator()
            it.InitTraversal()
            while not it.IsDoneWithTraversal():
                append.AddInputData(it.GetCurrentDataObject())
                it.GoToNextItem()
            append.Update()
            data = append.GetOutput()
        first = data.GetPoint(0) if data.GetNumberOfPoints() else (float("nan"),) * 3
        arrays = [data.GetPointData().GetArrayName(i) for i in range(data.GetPointData().GetNumberOfArrays())]
        arrays += [data.GetCellData().GetArrayName(i) for i in range(data.GetCellData().GetNumberOfArrays())]
        print("item", name, "points", data.GetNumberOfPoints(), "first", *[repr(x) for x in first],
              "bounds", *[repr(x) for x in data.GetBounds()], "arrays", *sorted(arrays))


def option(name, default=None):
    argv = getattr(sys, "argv", [])
    return argv[argv.index(name) + 1] if name in argv[:-1] else default


made, layout = build()
time_s = option("--time")
if time_s is not None:
    GetAnimationScene().AnimationTime = float(time_s)
if "--describe" in getattr(sys, "argv", []):
    describe(made, float(time_s or 0.0))
screenshot = option("--screenshot")
if screenshot is not None:
    SaveScreenshot(screenshot, layout, ImageResolution=[1600, 700])
    print("wrote", screenshot)
else:
    Render()
)PY";

// The colour scale's top for a per-triangle field: the value that 98 % of the part's area stays
// under (a tiny triangle hit once would otherwise set the scale, as in the impact maps).
double area_percentile_98(const ComponentAnalysis& a, double duration_s) {
    const TriangleFields& f = *a.fields;
    std::vector<std::pair<double, double>> rate_area;  // impacts per mm2 per s, m2
    for (std::size_t t = 0; t < f.triangle_count(); ++t) rate_area.emplace_back(f.rate_per_mm2_s(t, duration_s), f.area_m2(t));
    return area_percentile(std::move(rate_area), 0.98);
}

// m/s, the top of the speed colour scales (shot and impacts alike): the animation's scale when the
// scene records one, else the fastest impact or source.
double speed_scale(const SceneDescription& scene, double fastest_source_m_per_s, const std::vector<ComponentAnalysis>& parts) {
    if (scene.render) return scene.render->speed_scale_m_per_s;
    double fastest = fastest_source_m_per_s;
    for (const ComponentAnalysis& a : parts)
        for (std::size_t t = 0; t < a.fields->triangle_count(); ++t) fastest = std::max(fastest, a.fields->max_normal_speed(t));
    return fastest > 0.0 ? fastest : 1.0;
}

// The side the impacts came from (world frame at rest, unit; zero without impacts): the outward
// normals of the logged parts' triangles, each counted once per impact. The results view looks
// from there (from below at a sonotrode, from above under a nozzle).
Vec3 impacts_seen_from(const SceneDescription& scene, const std::vector<ComponentAnalysis>& parts) {
    Vec3 sum = Vec3::Zero();
    for (const ComponentAnalysis& a : parts) {
        const auto c =
            std::find_if(scene.components.begin(), scene.components.end(), [&](const ComponentDesc& d) { return d.name == a.name; });
        const Mat3 rotation = c != scene.components.end() ? c->rotation : Mat3::Identity();
        for (std::size_t t = 0; t < a.fields->triangle_count(); ++t) {
            const TriangleMesh& m = *a.mesh;
            const Vec3 n = (m.corner(t, 1) - m.corner(t, 0)).cross(m.corner(t, 2) - m.corner(t, 0));
            if (n.norm() > 0.0) sum += static_cast<double>(a.fields->count(t)) * (rotation * n.normalized());
        }
    }
    return sum.norm() > 0.0 ? Vec3(sum.normalized()) : Vec3::Zero();
}

}  // namespace

void write_paraview_script(const fs::path& run_dir, const fs::path& write_dir, const SceneDescription& scene, double fastest_source_m_per_s,
                           const std::vector<ComponentAnalysis>& parts, double run_duration_s, const AnalysisWindow& window) {
    const fs::path analysis = fs::absolute(run_dir / kAnalysisDirName);
    const Vec3& g = scene.process.gravity_m_per_s2;
    // (+ 0: the script's numbers never read -0, as the negated gravity's zeros would)
    const Vec3 up = (g.norm() > 0.0 ? Vec3(-g.normalized()) : Vec3(Vec3::UnitZ())) + Vec3::Zero();
    const Vec3 from = impacts_seen_from(scene, parts) + Vec3::Zero();
    nlohmann::json run = {{"analysis_dir", analysis.string()},
                          {"duration_s", run_duration_s},
                          {"window_from_s", window.from_s},
                          {"window_to_s", window.to_s},
                          {"up", {up.x(), up.y(), up.z()}},
                          {"speed_scale_mps", speed_scale(scene, fastest_source_m_per_s, parts)},
                          {"impacts_seen_from", {from.x(), from.y(), from.z()}},
                          {"assembly", std::string("../") + kParaviewDirName + "/" + kAssemblyFileName},
                          {"shots", std::string("../") + kParaviewDirName + "/" + kShotSeriesFileName},
                          {"parts", nlohmann::json::array()}};
    for (const ComponentAnalysis& a : parts) {
        run["parts"].push_back(
            {{"name", a.name},
             {"fields", a.name + ".vtp"},
             {"impacts", a.name + "_impacts.vtp"},
             {"impacts_per_mm2_s_scale", area_percentile_98(a, window.length_s())},
             {"coverage_series",
              a.coverage && scene.output.coverage_steps > 0 ? nlohmann::json(a.name + "_coverage_series.pvd") : nlohmann::json(nullptr)}});
    }
    const std::string script = "# ParaView view of the peensim run in " + fs::absolute(run_dir).lexically_normal().string() +
                               " (written by `peensim analyze`).\n"
                               "#   paraview --script=open_in_paraview.py          (or ParaView's Python Shell > Run Script)\n"
                               "#   pvbatch open_in_paraview.py --screenshot view.png [--time T] [--describe]   (no display: under Xvfb)\n"
                               "import json\n\n"
                               "RUN = json.loads(r\"\"\"" +
                               run.dump(1) + "\"\"\")\n" + kScriptBody;
    write_file_atomically((write_dir / kParaviewScriptFileName).string(), script);
}

}  // namespace peensim
