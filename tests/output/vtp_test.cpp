// The .vtp writers checked with a real VTK reader: VTK's Python modules in Debian's python3-paraview (installed by
// .ci/install-deps) reads each file with vtkXMLPolyDataReader and prints counts, array names
// and values (floats as Python repr, which round-trips exactly); the tests compare them with
// what was written, bit for bit. A missing VTK Python is a test failure, not a skip.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/box_mesh.h"
#include "output/peak_memory.h"
#include "output/vtk_collection.h"
#include "output/vtp_writer.h"
#include "support/shell_command.h"
#include "support/vtk_python.h"

namespace peensim {
namespace {

namespace fs = std::filesystem;

using testing::kSystemPython;  // Debian's, which sees python3-paraview's VTK

constexpr const char* kVtkDumpScript = R"PY(
import sys
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
r = vtkXMLPolyDataReader()
r.SetFileName(sys.argv[1])
r.Update()
d = r.GetOutput()
print("points", d.GetNumberOfPoints())
print("cells", d.GetNumberOfCells())
print("polys", d.GetNumberOfPolys())
print("verts", d.GetNumberOfVerts())
def chosen(n):
    return range(n) if sys.argv[2] == "all" else [int(i) for i in sys.argv[2].split(",")]
for i in chosen(d.GetNumberOfPoints()):
    print("point", i, *[repr(x) for x in d.GetPoint(i)])
for c in chosen(d.GetNumberOfCells()):
    ids = d.GetCell(c).GetPointIds()
    print("cell", c, d.GetCellType(c), *[ids.GetId(k) for k in range(ids.GetNumberOfIds())])
for section, attrs in (("CellData", d.GetCellData()), ("PointData", d.GetPointData())):
    for a in range(attrs.GetNumberOfArrays()):
        arr = attrs.GetArray(a)
        nc = arr.GetNumberOfComponents()
        print("array", section, arr.GetName(), nc, arr.GetNumberOfTuples(), arr.GetDataTypeAsString())
        for t in chosen(arr.GetNumberOfTuples()):
            print("value", arr.GetName(), t, *[repr(arr.GetComponent(t, k)) for k in range(nc)])
)PY";

constexpr int kVtkTriangle = 5;  // VTK cell type ids
constexpr int kVtkVertex = 1;

struct VtkArray {
    std::string section;  // CellData or PointData
    int components = 0;
    std::uint64_t tuples = 0;
    std::string type;
};

// What the VTK reader saw.
struct VtkDump {
    std::string output;  // the reader's whole output, for failure messages
    int exit_status = -1;
    std::map<std::string, std::uint64_t> counts;  // points, cells, polys, verts
    std::map<std::uint64_t, std::vector<double>> points;
    std::map<std::uint64_t, std::vector<long long>> cells;  // cell type, then point ids
    std::vector<std::string> array_names;                   // in file order
    std::map<std::string, VtkArray> arrays;
    std::map<std::string, std::map<std::uint64_t, std::vector<double>>> values;
};

std::string run(const std::string& command, int& exit_status) {
    peensim::testing::ShellResult r = peensim::testing::run_shell(command);
    exit_status = r.status;
    return std::move(r.output);
}

bool vtk_python_available(std::string& why) {
    int status = -1;
    why = run(std::string(kSystemPython) + " -c 'import vtkmodules.vtkIOXML'", status);
    return status == 0;
}

#define ASSERT_VTK_PYTHON()                                                                                       \
    do {                                                                                                          \
        std::string why;                                                                                          \
        ASSERT_TRUE(vtk_python_available(why))                                                                    \
            << "VTK's Python (python3-paraview) is missing (needed to check .vtp files with a real VTK reader): " \
            << "install it with `apt-get install python3-paraview` (.ci/install-deps does). " << why;             \
    } while (0)

// `indices`: "all" or a comma list of the point/cell/tuple indices to print.
VtkDump read_with_vtk(const fs::path& dir, const fs::path& vtp, const std::string& indices) {
    const fs::path script = dir / "vtk_dump.py";
    std::ofstream(script) << kVtkDumpScript;
    VtkDump dump;
    dump.output = run(std::string(kSystemPython) + " " + script.string() + " " + vtp.string() + " " + indices, dump.exit_status);
    std::istringstream lines(dump.output);
    std::string line;
    while (std::getline(lines, line)) {
        std::istringstream words(line);
        std::string key;
        words >> key;
        if (key == "point" || key == "value") {
            std::string name;
            if (key == "value") words >> name;
            std::uint64_t index = 0;
            words >> index;
            std::vector<double> numbers;
            std::string word;
            while (words >> word) numbers.push_back(std::strtod(word.c_str(), nullptr));
            if (key == "point")
                dump.points[index] = numbers;
            else
                dump.values[name][index] = numbers;
        } else if (key == "cell") {
            std::uint64_t index = 0;
            words >> index;
            long long id = 0;
            while (words >> id) dump.cells[index].push_back(id);
        } else if (key == "array") {
            std::string name;
            VtkArray a;
            words >> a.section >> name >> a.components >> a.tuples >> a.type;
            dump.array_names.push_back(name);
            dump.arrays[name] = a;
        } else if (!key.empty()) {
            words >> dump.counts[key];
        }
    }
    return dump;
}

class VtpWriterTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::string pattern = (fs::temp_directory_path() / "peensim-vtp-XXXXXX").string();
        ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
        dir_ = pattern;
    }
    void TearDown() override {
        if (!dir_.empty()) fs::remove_all(dir_);
    }
    // Files in the directory other than the VTK dump script.
    std::vector<std::string> files() const {
        std::vector<std::string> names;
        for (const auto& e : fs::directory_iterator(dir_)) {
            if (e.path().filename() != "vtk_dump.py") names.push_back(e.path().filename().string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }
    fs::path dir_;
};

// Value of cell field `field` (of `components`) for triangle t, component c: distinct for all.
double cell_value(int field, std::uint64_t t, int c) { return 1000.0 * field + static_cast<double>(t) + 0.125 * c + 1.0 / 3.0; }

TEST_F(VtpWriterTest, MeshWithTwoCellFieldsReadsBackExactlyInVtk) {
    ASSERT_VTK_PYTHON();
    BoxSpec spec;
    spec.size_m = Vec3(0.02, 0.03, 0.05);
    spec.center_m = Vec3(0.001, -0.002, 0.1);
    spec.divisions = Eigen::Vector3i(2, 1, 1);
    const TriangleMesh mesh = box(spec);
    const std::uint64_t n = mesh.triangle_count();
    std::vector<CellField> fields = {{"impact_count", 1, {}}, {"mean_velocity_m_per_s", 3, {}}};
    for (std::uint64_t t = 0; t < n; ++t) {
        fields[0].values.push_back(cell_value(0, t, 0));
        for (int c = 0; c < 3; ++c) fields[1].values.push_back(cell_value(1, t, c));
    }
    const fs::path vtp = dir_ / "part.vtp";
    write_mesh_vtp(vtp.string(), mesh, fields);
    EXPECT_EQ(files(), std::vector<std::string>{"part.vtp"});  // no .tmp left

    const VtkDump dump = read_with_vtk(dir_, vtp, "all");
    ASSERT_EQ(dump.exit_status, 0) << dump.output;
    EXPECT_EQ(dump.output.find("ERROR"), std::string::npos) << dump.output;
    EXPECT_EQ(dump.output.find("Warning"), std::string::npos) << dump.output;
    EXPECT_EQ(dump.counts.at("points"), mesh.vertices.size());
    EXPECT_EQ(dump.counts.at("cells"), n);
    EXPECT_EQ(dump.counts.at("polys"), n);
    EXPECT_EQ(dump.counts.at("verts"), 0u);
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        const Vec3& v = mesh.vertices[i];
        EXPECT_EQ(dump.points.at(i), (std::vector<double>{v.x(), v.y(), v.z()})) << "point " << i;
    }
    for (std::uint64_t t = 0; t < n; ++t) {
        const auto& tri = mesh.triangles[t];
        EXPECT_EQ(dump.cells.at(t), (std::vector<long long>{kVtkTriangle, tri[0], tri[1], tri[2]})) << "cell " << t;
    }
    EXPECT_EQ(dump.array_names, (std::vector<std::string>{"impact_count", "mean_velocity_m_per_s"}));
    EXPECT_EQ(dump.arrays.at("impact_count").section, "CellData");
    EXPECT_EQ(dump.arrays.at("impact_count").components, 1);
    EXPECT_EQ(dump.arrays.at("mean_velocity_m_per_s").components, 3);
    EXPECT_EQ(dump.arrays.at("mean_velocity_m_per_s").tuples, n);
    EXPECT_EQ(dump.arrays.at("mean_velocity_m_per_s").type, "double");
    for (std::uint64_t t = 0; t < n; ++t) {
        EXPECT_EQ(dump.values.at("impact_count").at(t), (std::vector<double>{cell_value(0, t, 0)}));
        EXPECT_EQ(dump.values.at("mean_velocity_m_per_s").at(t),
                  (std::vector<double>{cell_value(1, t, 0), cell_value(1, t, 1), cell_value(1, t, 2)}));
    }
}

ImpactRecord impact_number(std::uint64_t i) {
    const double x = static_cast<double>(i);
    ImpactRecord r;
    r.time_s = 1e-4 * x + 1.0 / 7.0;
    r.point_m = Vec3(0.001 * x, -0.002 * x + 0.1, 0.5 / (x + 1.0));
    r.v_in_m_per_s = Vec3(1.5 + x, -2.25 - x, 3.0 / (x + 3.0));
    r.vn_in_m_per_s = 4.0 + 1.0 / (x + 1.0);
    return r;
}

TEST_F(VtpWriterTest, StreamedImpactPointsReadBackExactlyInVtk) {
    ASSERT_VTK_PYTHON();
    const fs::path vtp = dir_ / "impacts.vtp";
    constexpr std::uint64_t kSingles = 5;
    constexpr std::uint64_t kChunk = 3;
    {
        ImpactPointsVtpWriter writer(vtp.string(), impact_point_field_layouts());
        for (std::uint64_t i = 0; i < kSingles; ++i) writer.add(impact_number(i));
        // A chunk of the same impacts, through the generic chunk API.
        std::vector<Vec3> points;
        std::vector<PointField> chunk = {{"v_in_mps", 3, {}}, {"vn_in_mps", 1, {}}, {"time_s", 1, {}}};
        for (std::uint64_t i = kSingles; i < kSingles + kChunk; ++i) {
            const ImpactRecord r = impact_number(i);
            points.push_back(r.point_m);
            for (int c = 0; c < 3; ++c) chunk[0].values.push_back(r.v_in_m_per_s[c]);
            chunk[1].values.push_back(r.vn_in_m_per_s);
            chunk[2].values.push_back(r.time_s);
        }
        writer.add(points, chunk);
        EXPECT_EQ(files().size(), 4u);  // points + 3 field scratch files while streaming
        EXPECT_FALSE(fs::exists(vtp));
        writer.finish();
        EXPECT_EQ(writer.points_written(), kSingles + kChunk);
    }
    EXPECT_EQ(files(), std::vector<std::string>{"impacts.vtp"});  // scratch files and .tmp gone

    const std::uint64_t n = kSingles + kChunk;
    const VtkDump dump = read_with_vtk(dir_, vtp, "all");
    ASSERT_EQ(dump.exit_status, 0) << dump.output;
    EXPECT_EQ(dump.output.find("ERROR"), std::string::npos) << dump.output;
    EXPECT_EQ(dump.counts.at("points"), n);
    EXPECT_EQ(dump.counts.at("cells"), n);
    EXPECT_EQ(dump.counts.at("verts"), n);
    EXPECT_EQ(dump.counts.at("polys"), 0u);
    EXPECT_EQ(dump.array_names, (std::vector<std::string>{"v_in_mps", "vn_in_mps", "time_s"}));
    EXPECT_EQ(dump.arrays.at("v_in_mps").section, "PointData");
    EXPECT_EQ(dump.arrays.at("v_in_mps").components, 3);
    EXPECT_EQ(dump.arrays.at("time_s").tuples, n);
    for (std::uint64_t i = 0; i < n; ++i) {
        const ImpactRecord r = impact_number(i);
        EXPECT_EQ(dump.points.at(i), (std::vector<double>{r.point_m.x(), r.point_m.y(), r.point_m.z()}));
        EXPECT_EQ(dump.cells.at(i), (std::vector<long long>{kVtkVertex, static_cast<long long>(i)}));
        EXPECT_EQ(dump.values.at("v_in_mps").at(i), (std::vector<double>{r.v_in_m_per_s.x(), r.v_in_m_per_s.y(), r.v_in_m_per_s.z()}));
        EXPECT_EQ(dump.values.at("vn_in_mps").at(i), std::vector<double>{r.vn_in_m_per_s});
        EXPECT_EQ(dump.values.at("time_s").at(i), std::vector<double>{r.time_s});
    }
}

TEST_F(VtpWriterTest, UnfinishedPointWriterLeavesNothingBehind) {
    const fs::path vtp = dir_ / "impacts.vtp";
    std::ofstream(vtp) << "previous run";
    {
        ImpactPointsVtpWriter writer(vtp.string(), impact_point_field_layouts());
        writer.add(impact_number(0));
    }
    EXPECT_EQ(files(), std::vector<std::string>{"impacts.vtp"});
    std::ifstream in(vtp);
    std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(content, "previous run");  // the old file is untouched
}

TEST_F(VtpWriterTest, RejectsFieldsThatDoNotFit) {
    const TriangleMesh mesh = box(BoxSpec{});
    const std::string path = (dir_ / "m.vtp").string();
    EXPECT_THROW(write_mesh_vtp(path, mesh, {{"count", 1, std::vector<double>(mesh.triangle_count() + 1)}}), std::invalid_argument);
    EXPECT_THROW(write_mesh_vtp(path, mesh, {{"a<b", 1, std::vector<double>(mesh.triangle_count())}}), std::invalid_argument);
    EXPECT_THROW(
        write_mesh_vtp(path, mesh,
                       {{"c", 1, std::vector<double>(mesh.triangle_count())}, {"c", 1, std::vector<double>(mesh.triangle_count())}}),
        std::invalid_argument);
    EXPECT_TRUE(files().empty());

    ImpactPointsVtpWriter writer((dir_ / "p.vtp").string(), {{"speed", 1}});
    EXPECT_THROW(writer.add(impact_number(0)), std::logic_error);  // not the impact layout
    const double two[2] = {1.0, 2.0};
    EXPECT_THROW(writer.add(Vec3::Zero(), two), std::invalid_argument);
    writer.finish();
    EXPECT_THROW(writer.add(Vec3::Zero(), std::span<const double>(two, 1)), std::logic_error);
}

TEST_F(VtpWriterTest, HalfMillionTriangleMeshWriteTimeAndSize) {
    ASSERT_VTK_PYTHON();
    BoxSpec spec;
    spec.size_m = Vec3(0.05, 0.05, 0.05);
    spec.divisions = Eigen::Vector3i(205, 205, 205);  // 12 * 205^2 = 504300 triangles
    const TriangleMesh mesh = box(spec);
    const std::uint64_t n = mesh.triangle_count();
    ASSERT_EQ(n, 504300u);
    // The six impact-analysis fields the next issue writes.
    std::vector<CellField> fields = {{"impact_count", 1, {}},
                                     {"impacts_per_mm2_per_s", 1, {}},
                                     {"mean_normal_speed_m_per_s", 1, {}},
                                     {"max_normal_speed_m_per_s", 1, {}},
                                     {"energy_J_per_m2", 1, {}},
                                     {"coverage", 1, {}}};
    for (int f = 0; f < 6; ++f) {
        fields[static_cast<std::size_t>(f)].values.resize(n);
        for (std::uint64_t t = 0; t < n; ++t) fields[static_cast<std::size_t>(f)].values[t] = cell_value(f, t, 0);
    }
    const fs::path vtp = dir_ / "gear.vtp";
    const auto start = std::chrono::steady_clock::now();
    write_mesh_vtp(vtp.string(), mesh, fields);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::uintmax_t bytes = fs::file_size(vtp);
    std::printf("[ vtp      ] %llu triangles, %zu vertices, 6 cell fields: wrote %.1f MB in %.3f s\n", static_cast<unsigned long long>(n),
                mesh.vertices.size(), static_cast<double>(bytes) / 1e6, seconds);
    // Raw binary: 24 B per vertex, 8 B per connectivity entry (3 per triangle) and offset, 8 B per field value.
    const std::uint64_t data = 24 * mesh.vertices.size() + (3 + 1 + 6) * 8 * n + 9 * 8;
    EXPECT_GT(bytes, data);
    EXPECT_LT(bytes, data + 4096);  // plus the XML header

    const std::string last = std::to_string(n - 1);
    const VtkDump dump = read_with_vtk(dir_, vtp, "0,1," + last);
    ASSERT_EQ(dump.exit_status, 0) << dump.output;
    EXPECT_EQ(dump.counts.at("cells"), n);
    EXPECT_EQ(dump.counts.at("points"), mesh.vertices.size());
    EXPECT_EQ(dump.array_names.size(), 6u);
    const auto& tri = mesh.triangles[n - 1];
    EXPECT_EQ(dump.cells.at(n - 1), (std::vector<long long>{kVtkTriangle, tri[0], tri[1], tri[2]}));
    EXPECT_EQ(dump.values.at("coverage").at(n - 1), std::vector<double>{cell_value(5, n - 1, 0)});
    EXPECT_EQ(dump.values.at("impact_count").at(1), std::vector<double>{cell_value(0, 1, 0)});
}

// bytes, the kernel's peak resident set (VmHWM) of this process.
std::uint64_t vm_hwm_bytes() {
    std::ifstream status("/proc/self/status");
    std::string word;
    while (status >> word) {
        if (word == "VmHWM:") {
            std::uint64_t kib = 0;
            status >> kib;
            return kib * 1024u;
        }
    }
    return 0;
}

// "5" in clear_refs resets VmHWM to the current RSS (Linux >= 4.0), so that a growth measured
// after it is the following code's alone.
bool reset_peak_rss() {
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";
    clear.flush();
    return clear.good();
}

TEST_F(VtpWriterTest, MillionImpactsStreamWithBoundedMemory) {
    ASSERT_VTK_PYTHON();
    // Earlier tests in this process may have set a higher peak: reset it first.
    ASSERT_TRUE(reset_peak_rss()) << "cannot reset the peak RSS through /proc/self/clear_refs";
    const std::uint64_t hwm_before = vm_hwm_bytes();
    ASSERT_GT(hwm_before, 0u);

    constexpr std::uint64_t kImpacts = 1'000'000;
    const fs::path vtp = dir_ / "impacts.vtp";
    const auto start = std::chrono::steady_clock::now();
    {
        ImpactPointsVtpWriter writer(vtp.string(), impact_point_field_layouts());
        for (std::uint64_t i = 0; i < kImpacts; ++i) writer.add(impact_number(i));
        writer.finish();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::uint64_t growth = vm_hwm_bytes() - hwm_before;
    const std::uintmax_t bytes = fs::file_size(vtp);
    std::printf(
        "[ vtp      ] %llu impacts streamed: %.1f MB in %.3f s, peak RSS growth %.1f MiB, "
        "process peak RSS %.1f MiB\n",
        static_cast<unsigned long long>(kImpacts), static_cast<double>(bytes) / 1e6, seconds, static_cast<double>(growth) / 1048576.0,
        static_cast<double>(peak_resident_bytes()) / 1048576.0);
    // Holding the impacts would take 64 MB (8 doubles each); the writer's buffers are 5 MiB.
    EXPECT_LT(growth, std::uint64_t{16} << 20);
    {  // Control: the same measurement does see the 64 MB the impacts would take if held.
        ASSERT_TRUE(reset_peak_rss());
        const std::uint64_t hwm = vm_hwm_bytes();
        std::vector<double> held(kImpacts * 8, 1.0);
        EXPECT_GT(vm_hwm_bytes() - hwm, held.size() * sizeof(double) * 7 / 8);
    }
    EXPECT_GT(bytes, kImpacts * (3 + 2 + 3 + 1 + 1) * 8);

    const VtkDump dump = read_with_vtk(dir_, vtp, "0,123456,999999");
    ASSERT_EQ(dump.exit_status, 0) << dump.output;
    EXPECT_EQ(dump.counts.at("points"), kImpacts);
    EXPECT_EQ(dump.counts.at("verts"), kImpacts);
    for (std::uint64_t i : {0ull, 123456ull, 999999ull}) {
        const ImpactRecord r = impact_number(i);
        EXPECT_EQ(dump.points.at(i), (std::vector<double>{r.point_m.x(), r.point_m.y(), r.point_m.z()}));
        EXPECT_EQ(dump.values.at("v_in_mps").at(i), (std::vector<double>{r.v_in_m_per_s.x(), r.v_in_m_per_s.y(), r.v_in_m_per_s.z()}));
        EXPECT_EQ(dump.values.at("time_s").at(i), std::vector<double>{r.time_s});
    }
}

// Int32, Int64 and Float64 arrays on points and cells, and field data (numbers, a text), as the
// ParaView outputs use them (tests/app/paraview/paraview_outputs_test.cpp): read back exactly.
TEST_F(VtpWriterTest, TypedArraysAndFieldDataReadBackExactlyInVtk) {
    const fs::path vtp = dir_ / "typed.vtp";
    PolyDataLayout layout{3,
                          PolyDataLayout::Cells::vertices,
                          0,
                          {{"shot", VtkType::int64, 1}, {"v_mps", VtkType::float64, 3}},
                          {{"role", VtkType::int32, 1}},
                          {{"time_s", std::vector<double>{0.1}},
                           {"component", std::string("gear-1")},
                           {"pose_rotation", std::vector<double>{1.0 / 3.0, -2.5e-300, 7.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0}}}};
    PolyDataWriter out(vtp.string(), layout);
    const std::vector<Vec3> points = {Vec3(0.1, 0.2, 0.3), Vec3(-1.0 / 7.0, 0.0, 1e-20), Vec3(5.0, 6.0, 7.0)};
    out.add_points(points);
    for (const std::int64_t shot : std::vector<std::int64_t>{7, 123456789012, -1}) out.add(shot);
    for (int i = 0; i < 9; ++i) out.add(0.5 * i + 1.0 / 3.0);
    for (std::int32_t role : {0, 2, 4}) out.add(role);
    EXPECT_FALSE(fs::exists(vtp));
    out.finish();
    EXPECT_EQ(files(), std::vector<std::string>{"typed.vtp"});

    const testing::VtkReadPolyData d = testing::read_vtp_with_vtk(vtp.string());
    EXPECT_EQ(d.points, 3u);
    EXPECT_EQ(d.verts, 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(d.coordinates[i], (std::array<double, 3>{points[i].x(), points[i].y(), points[i].z()}));
        EXPECT_EQ(d.cell_points[i], (std::vector<long long>{kVtkVertex, static_cast<long long>(i)}));
    }
    EXPECT_EQ(d.point_array_names, (std::vector<std::string>{"shot", "v_mps"}));
    EXPECT_EQ(d.point_data.at("shot").type, "long long");
    EXPECT_EQ(d.point_data.at("shot").values, (std::vector<double>{7.0, 123456789012.0, -1.0}));
    EXPECT_EQ(d.point_data.at("v_mps").components, 3);
    for (int i = 0; i < 9; ++i) EXPECT_EQ(d.point_data.at("v_mps").values[static_cast<std::size_t>(i)], 0.5 * i + 1.0 / 3.0);
    EXPECT_EQ(d.cell_data.at("role").type, "int");
    EXPECT_EQ(d.cell_data.at("role").values, (std::vector<double>{0.0, 2.0, 4.0}));
    EXPECT_EQ(d.field_numbers("time_s"), std::vector<double>{0.1});
    EXPECT_EQ(d.field_text("component"), "gear-1");
    EXPECT_EQ(d.field_numbers("pose_rotation"), (std::vector<double>{1.0 / 3.0, -2.5e-300, 7.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0}));
}

TEST_F(VtpWriterTest, PolyDataWriterRefusesValuesOutOfTheLayoutsOrder) {
    const std::string path = (dir_ / "order.vtp").string();
    PolyDataLayout layout{1, PolyDataLayout::Cells::vertices, 0, {{"shot", VtkType::int64, 1}}, {}, {}};
    {
        PolyDataWriter out(path, layout);
        EXPECT_THROW(out.add(1.0), std::logic_error);  // a value where the points are due
        EXPECT_THROW(out.add_triangle({0, 0, 0}), std::logic_error);
        out.add_point(Vec3::Zero());
        EXPECT_THROW(out.add(1.0), std::logic_error);  // a double where the Int64 array is due
        EXPECT_THROW(out.finish(), std::logic_error);  // `shot` has no value yet
    }
    EXPECT_TRUE(files().empty());  // an unfinished file leaves nothing
    {
        PolyDataWriter out(path, layout);
        out.add_point(Vec3::Zero());
        out.add(std::int64_t{3});
        EXPECT_THROW(out.add(std::int64_t{4}), std::logic_error);  // past the last array
        out.finish();
    }
    EXPECT_EQ(files(), std::vector<std::string>{"order.vtp"});
    layout.triangles = 1;  // triangles in a file of vertices
    EXPECT_THROW(PolyDataWriter(path + "2", layout), std::invalid_argument);
    layout.triangles = 0;
    layout.field_data = {{"a&b", std::vector<double>{1.0}}};
    EXPECT_THROW(PolyDataWriter(path + "2", layout), std::invalid_argument);
    layout.field_data = {{"empty", std::vector<double>{}}};
    EXPECT_THROW(PolyDataWriter(path + "2", layout), std::invalid_argument);
    EXPECT_EQ(files(), std::vector<std::string>{"order.vtp"});
}

TEST_F(VtpWriterTest, TimeSeriesAndMultiblockReadBackInVtk) {
    fs::create_directories(dir_ / "steps");
    const std::vector<TimeStepFile> steps = {{0.0, "steps/a.vtp"}, {0.005, "steps/b.vtp"}, {1.0 / 3.0, "steps/c.vtp"}};
    for (std::size_t k = 0; k < steps.size(); ++k) {
        PolyDataLayout layout{k, PolyDataLayout::Cells::vertices, 0, {}, {}, {{"time_s", std::vector<double>{steps[k].time_s}}}};
        PolyDataWriter out((dir_ / steps[k].file).string(), layout);
        for (std::size_t i = 0; i < k; ++i) out.add_point(Vec3(static_cast<double>(i), 0.0, 0.0));
        out.finish();
    }
    write_pvd((dir_ / "series.pvd").string(), steps);
    const std::vector<testing::VtkReadStep> read = testing::read_pvd_with_vtk((dir_ / "series.pvd").string());
    ASSERT_EQ(read.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(read[k].time_s, steps[k].time_s);  // shortest round-trip text: exact
        EXPECT_EQ(read[k].file, steps[k].file);
        EXPECT_EQ(read[k].data.points, k);
        EXPECT_EQ(read[k].data.field_numbers("time_s"), std::vector<double>{steps[k].time_s});
    }

    const BoxSpec spec;
    write_mesh_vtp((dir_ / "steps" / "box.vtp").string(), box(spec), {}, {{"component", std::string("box")}});
    const std::vector<NamedBlock> blocks = {{"first", "steps/b.vtp"}, {"box", "steps/box.vtp"}};
    write_vtm((dir_ / "assembly.vtm").string(), blocks);
    const std::vector<testing::VtkReadBlock> got = testing::read_vtm_with_vtk((dir_ / "assembly.vtm").string());
    ASSERT_EQ(got.size(), 2u);
    EXPECT_EQ(got[0].name, "first");
    EXPECT_EQ(got[0].data.points, 1u);
    EXPECT_EQ(got[1].name, "box");
    EXPECT_EQ(got[1].data.polys, box(spec).triangle_count());
    EXPECT_EQ(got[1].data.field_text("component"), "box");
}

}  // namespace
}  // namespace peensim
