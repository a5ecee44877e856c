// ParaView files read back with VTK's own readers (VTK's Python modules of Debian's python3-paraview, run as a child python3):
// a .vtp with vtkXMLPolyDataReader, a .vtm with vtkXMLMultiBlockDataReader (its blocks by name),
// a .pvd's steps (the collection's XML, each step's file with vtkXMLPolyDataReader). Everything
// the reader saw comes back as values (floats printed in Python's repr, which round-trips), so
// tests compare what was written bit for bit.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace peensim::testing {

// Debian's interpreter: python3-paraview installs VTK into /usr/lib/python3/dist-packages, which a
// python3 earlier on PATH (pyenv, venv) does not see.
inline constexpr const char* kSystemPython = "/usr/bin/python3";

struct VtkReadArray {
    std::string type;  // VTK's name of the value type: "double", "int", "long", "long long"...
    int components = 0;
    std::uint64_t tuples = 0;
    std::vector<double> values;  // tuple by tuple
};

struct VtkReadPolyData {
    std::uint64_t points = 0, cells = 0, verts = 0, polys = 0;
    std::vector<std::array<double, 3>> coordinates;
    std::vector<std::vector<long long>> cell_points;               // per cell: its VTK type, then its point ids
    std::vector<std::string> point_array_names, cell_array_names;  // in file order
    std::map<std::string, VtkReadArray> point_data, cell_data;
    std::map<std::string, std::variant<std::string, std::vector<double>>> field_data;

    const std::vector<double>& field_numbers(const std::string& name) const { return std::get<std::vector<double>>(field_data.at(name)); }
    const std::string& field_text(const std::string& name) const { return std::get<std::string>(field_data.at(name)); }
};

struct VtkReadBlock {
    std::string name;
    VtkReadPolyData data;
};

struct VtkReadStep {
    double time_s = 0.0;
    std::string file;  // as the .pvd names it
    VtkReadPolyData data;
};

// What went wrong is thrown as std::runtime_error with the reader's whole output (a missing
// VTK's Python included: a test failure, not a skip).
VtkReadPolyData read_vtp_with_vtk(const std::string& path);
std::vector<VtkReadBlock> read_vtm_with_vtk(const std::string& path);
std::vector<VtkReadStep> read_pvd_with_vtk(const std::string& path);

}  // namespace peensim::testing
