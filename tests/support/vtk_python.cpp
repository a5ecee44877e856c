#include "support/vtk_python.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "support/shell_command.h"

namespace peensim::testing {

namespace {

// Prints one JSON document: the file's content as VTK's readers see it.
constexpr const char* kDumpScript = R"PY(
import json, math, os, sys
import xml.etree.ElementTree as ElementTree
from vtkmodules.vtkCommonCore import vtkStringArray
from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet
from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataReader, vtkXMLPolyDataReader
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkFileOutputWindow

window = vtkFileOutputWindow()
window.SetFileName(sys.argv[2])
vtkOutputWindow.SetInstance(window)

def number(x):  # JSON has no NaN or infinity: those go as text ("nan", "inf", "-inf")
    return x if math.isfinite(x) else repr(x)

def arrays(attributes):
    out, names = {}, []
    for i in range(attributes.GetNumberOfArrays()):
        a = attributes.GetArray(i)
        names.append(a.GetName())
        nc = a.GetNumberOfComponents()
        out[a.GetName()] = {"type": a.GetDataTypeAsString(), "components": nc, "tuples": a.GetNumberOfTuples(),
                            "values": [number(a.GetComponent(t, c)) for t in range(a.GetNumberOfTuples()) for c in range(nc)]}
    return out, names

def polydata(d):
    fields = {}
    fd = d.GetFieldData()
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        if isinstance(a, vtkStringArray):
            fields[a.GetName()] = {"text": a.GetValue(0)}
        else:
            fields[a.GetName()] = {"numbers": [a.GetComponent(0, c) for c in range(a.GetNumberOfComponents())]}
    point_data, point_names = arrays(d.GetPointData())
    cell_data, cell_names = arrays(d.GetCellData())
    cells = []
    for c in range(d.GetNumberOfCells()):
        ids = d.GetCell(c).GetPointIds()
        cells.append([d.GetCellType(c)] + [ids.GetId(k) for k in range(ids.GetNumberOfIds())])
    return {"points": d.GetNumberOfPoints(), "cells": d.GetNumberOfCells(), "verts": d.GetNumberOfVerts(),
            "polys": d.GetNumberOfPolys(), "coordinates": [list(d.GetPoint(i)) for i in range(d.GetNumberOfPoints())],
            "cell_points": cells, "point_data": point_data, "cell_data": cell_data, "point_names": point_names,
            "cell_names": cell_names, "field_data": fields}

def read_vtp(path):
    if not os.path.exists(path):
        raise SystemExit("no file " + path)
    r = vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    return polydata(r.GetOutput())

path = sys.argv[1]
if path.endswith(".vtm"):
    r = vtkXMLMultiBlockDataReader()
    r.SetFileName(path)
    r.Update()
    m = r.GetOutput()
    result = {"blocks": [{"name": m.GetMetaData(i).Get(vtkCompositeDataSet.NAME()), "data": polydata(m.GetBlock(i))}
                         for i in range(m.GetNumberOfBlocks())]}
elif path.endswith(".pvd"):
    steps = []
    for d in ElementTree.parse(path).getroot().iter("DataSet"):
        steps.append({"time": float(d.get("timestep")), "file": d.get("file"),
                      "data": read_vtp(os.path.join(os.path.dirname(path), d.get("file")))})
    result = {"steps": steps}
else:
    result = read_vtp(path)
print(json.dumps(result))
)PY";

nlohmann::json run_dump(const std::string& path) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path();
    const std::string script = (dir / ("peensim_vtk_dump_" + std::to_string(::getpid()) + ".py")).string();
    const std::string messages = script + ".messages";
    std::ofstream(script) << kDumpScript;
    std::remove(messages.c_str());
    const auto [status, output] = run_shell(std::string(kSystemPython) + " " + script + " '" + path + "' '" + messages + "'");
    std::ifstream in(messages);
    const std::string vtk_messages((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::remove(script.c_str());
    std::remove(messages.c_str());
    if (status != 0) throw std::runtime_error("VTK's reader failed on " + path + ": " + output.substr(0, 4000));
    if (!vtk_messages.empty()) throw std::runtime_error("VTK's reader complained about " + path + ": " + vtk_messages.substr(0, 4000));
    try {
        return nlohmann::json::parse(output);
    } catch (const std::exception& e) {
        throw std::runtime_error("unreadable output of VTK's reader on " + path + ": " + e.what() + ": " + output.substr(0, 4000));
    }
}

VtkReadArray array_of(const nlohmann::json& j) {
    std::vector<double> values;
    values.reserve(j["values"].size());
    for (const nlohmann::json& v : j["values"]) values.push_back(v.is_string() ? std::stod(v.get<std::string>()) : v.get<double>());
    return {j["type"].get<std::string>(), j["components"].get<int>(), j["tuples"].get<std::uint64_t>(), std::move(values)};
}

VtkReadPolyData polydata_of(const nlohmann::json& j) {
    VtkReadPolyData d;
    d.points = j["points"].get<std::uint64_t>();
    d.cells = j["cells"].get<std::uint64_t>();
    d.verts = j["verts"].get<std::uint64_t>();
    d.polys = j["polys"].get<std::uint64_t>();
    for (const auto& p : j["coordinates"]) d.coordinates.push_back({p[0].get<double>(), p[1].get<double>(), p[2].get<double>()});
    d.cell_points = j["cell_points"].get<std::vector<std::vector<long long>>>();
    d.point_array_names = j["point_names"].get<std::vector<std::string>>();
    d.cell_array_names = j["cell_names"].get<std::vector<std::string>>();
    for (const auto& [name, a] : j["point_data"].items()) d.point_data[name] = array_of(a);
    for (const auto& [name, a] : j["cell_data"].items()) d.cell_data[name] = array_of(a);
    for (const auto& [name, f] : j["field_data"].items()) {
        if (f.contains("text"))
            d.field_data[name] = f["text"].get<std::string>();
        else
            d.field_data[name] = f["numbers"].get<std::vector<double>>();
    }
    return d;
}

}  // namespace

VtkReadPolyData read_vtp_with_vtk(const std::string& path) { return polydata_of(run_dump(path)); }

std::vector<VtkReadBlock> read_vtm_with_vtk(const std::string& path) {
    std::vector<VtkReadBlock> blocks;
    const nlohmann::json dump = run_dump(path);  // outlives the loop (a temporary's member would not)
    for (const auto& b : dump["blocks"]) blocks.push_back({b["name"].get<std::string>(), polydata_of(b["data"])});
    return blocks;
}

std::vector<VtkReadStep> read_pvd_with_vtk(const std::string& path) {
    std::vector<VtkReadStep> steps;
    const nlohmann::json dump = run_dump(path);
    for (const auto& s : dump["steps"]) steps.push_back({s["time"].get<double>(), s["file"].get<std::string>(), polydata_of(s["data"])});
    return steps;
}

}  // namespace peensim::testing
