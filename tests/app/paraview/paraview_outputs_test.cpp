// The ParaView outputs of a run and its analysis (docs/user-guide.md, "ParaView files"), read back with VTK's own
// readers (VTK's Python from python3-paraview, tests/support/vtk_python.h): the assembly in the world frame at t = 0,
// the shot-position series against the closed-form flight and across a resume, the moving
// components' poses, the coverage series against the analysis' coverage curve, the field names of
// every file; and the ParaView script run by ParaView itself (pvbatch under Xvfb), rendering a
// frame and posing the files at a time.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/analysis/analyze_job.h"
#include "app/paraview/paraview_assembly.h"
#include "app/run/run_job.h"
#include "model/model.h"
#include "scene/scene_parser.h"
#include "support/files.h"
#include "support/run_in_process.h"
#include "support/shell_command.h"
#include "support/temp_dir.h"
#include "support/test_scene.h"
#include "support/vtk_python.h"

namespace peensim {
namespace {

namespace fs = std::filesystem;
using testing::InProcessRun;
using testing::TempDir;
using testing::TestScene;
using testing::TestSceneSpec;

const std::string kGear = std::string(PEENSIM_SOURCE_DIR) + "/scenes/gear.yaml";
const std::string kRotatingGear = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rotating-gear.yaml";
constexpr int kVtkTriangle = 5;  // VTK cell type ids
constexpr int kVtkVertex = 1;

std::vector<double> numbers(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

// Every regular file under `dir` (relative path -> bytes).
std::map<std::string, std::string> files_under(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = testing::read_file(e.path());
    return files;
}

TEST(ParaviewAssembly, EveryComponentWithItsRoleInTheWorldFrameAtTimeZero) {
    TempDir dir;
    const auto r = testing::run_in_process({kRotatingGear, dir.path.string(), false, false, {}, {"process.duration=0.01"}});
    ASSERT_EQ(r.code, kExitOk) << r.err;
    const auto model = compile_model(parse_scene_file(kRotatingGear));
    const std::vector<testing::VtkReadBlock> blocks = testing::read_vtm_with_vtk((dir.path / "paraview" / "assembly.vtm").string());
    ASSERT_EQ(blocks.size(), model->components.size());
    std::set<std::string> roles;
    for (std::size_t i = 0; i < blocks.size(); ++i) {
        const Component& c = model->components[i];
        const testing::VtkReadPolyData& d = blocks[i].data;
        SCOPED_TRACE(c.name);
        EXPECT_EQ(blocks[i].name, c.name);
        EXPECT_EQ(d.field_text("component"), c.name);
        EXPECT_EQ(d.field_text("role_name"), role_name(c.role));
        roles.insert(d.field_text("role_name"));
        ASSERT_EQ(d.points, c.mesh->vertices.size());
        ASSERT_EQ(d.polys, c.mesh->triangle_count());
        const Pose at_start = c.kinematics.pose(SimTime{});
        for (std::size_t v = 0; v < c.mesh->vertices.size(); v += 97) {
            const Vec3 w = at_start.to_world(c.mesh->vertices[v]);
            EXPECT_EQ(d.coordinates[v], (std::array<double, 3>{w.x(), w.y(), w.z()})) << "vertex " << v;
        }
        const auto& tri = c.mesh->triangles.back();
        EXPECT_EQ(d.cell_points.back(), (std::vector<long long>{kVtkTriangle, tri[0], tri[1], tri[2]}));
        const testing::VtkReadArray& role = d.cell_data.at("role");
        EXPECT_EQ(role.type, "int");
        EXPECT_EQ(role.tuples, c.mesh->triangle_count());
        EXPECT_TRUE(std::all_of(role.values.begin(), role.values.end(), [&](double x) { return x == static_cast<int>(c.role); }));
        // The motion, to pose it at any time.
        const Kinematics& k = c.kinematics;
        EXPECT_EQ(d.field_numbers("pose_translation_m"), numbers(k.rest.translation));
        EXPECT_EQ(d.field_numbers("pose_rotation").size(), 9u);
        if (c.role == ComponentRole::sonotrode) {
            EXPECT_EQ(d.field_text("motion"), "vibrating");
            EXPECT_EQ(d.field_numbers("amplitude_m"), std::vector<double>{25e-6});
            EXPECT_EQ(d.field_numbers("frequency_hz"), std::vector<double>{20e3});
            EXPECT_EQ(d.field_numbers("vibration_axis"), numbers(k.axis));
        } else if (c.name == "gear") {
            EXPECT_EQ(d.field_text("motion"), "rotating");
            EXPECT_DOUBLE_EQ(d.field_numbers("angular_speed_rad_per_s").at(0), M_PI);  // 30 rpm
            EXPECT_EQ(d.field_numbers("axis_direction"), numbers(k.axis_direction));
            EXPECT_EQ(d.field_numbers("axis_point_m"), numbers(k.axis_point_m));
        } else {
            EXPECT_EQ(d.field_text("motion"), "fixed");
        }
    }
    EXPECT_EQ(roles, (std::set<std::string>{"sonotrode", "chamber", "fixture", "part"}));
    // The shot series is off unless the scene asks for it.
    EXPECT_FALSE(fs::exists(dir.path / "paraview" / "shots.pvd"));
    EXPECT_FALSE(fs::exists(dir.path / "paraview" / "shots"));
}

// One shot thrown straight up from a still plate: until it falls back (0.102 s) its flight is
// p0 + v0 t + g t^2 / 2 exactly, and every step of the series must be there.
class ShotSeriesFlight : public ::testing::TestWithParam<const char*> {};

TEST_P(ShotSeriesFlight, StepsAreTheClosedFormFlightAtTheirTimes) {
    TestSceneSpec spec;
    spec.shot_count = 1;
    spec.amplitude_m = 0.0;
    spec.initial_velocity_m_per_s = Vec3(0.0, 0.0, 0.5);
    spec.duration_s = 0.08;
    spec.scheme = GetParam();
    const TestScene scene(spec);
    const std::string out = scene.make_subdirectory("run");
    const auto r = testing::run_in_process({scene.scene_path(), out, false, false, {}, {"output.shot_positions=10 ms"}});
    ASSERT_EQ(r.code, kExitOk) << r.err;
    EXPECT_NE(r.out.find("shot positions: " + out + "/paraview/shots.pvd (9 steps, every 0.01 s; writing took "), std::string::npos)
        << r.out;

    const std::vector<testing::VtkReadStep> steps = testing::read_pvd_with_vtk(out + "/paraview/shots.pvd");
    ASSERT_EQ(steps.size(), 9u);
    const std::array<double, 3> p0 = steps[0].data.coordinates.at(0);
    const Vec3 g = spec.gravity_m_per_s2;
    for (std::size_t k = 0; k < steps.size(); ++k) {
        SCOPED_TRACE("step " + std::to_string(k));
        const testing::VtkReadPolyData& d = steps[k].data;
        const double t = static_cast<double>(k) * 0.01;
        EXPECT_EQ(steps[k].time_s, t);
        EXPECT_EQ(d.field_numbers("time_s"), std::vector<double>{t});
        char name[64];
        std::snprintf(name, sizeof name, "shots/shots_%06zu.vtp", k);
        EXPECT_EQ(steps[k].file, name);
        ASSERT_EQ(d.points, 1u);
        ASSERT_EQ(d.verts, 1u);
        EXPECT_EQ(d.cell_points.at(0), (std::vector<long long>{kVtkVertex, 0}));
        EXPECT_EQ(d.point_array_names, (std::vector<std::string>{"shot", "v_mps", "speed_mps", "shot_diameter_m"}));
        const Vec3 v = *spec.initial_velocity_m_per_s + g * t;
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(d.coordinates[0][static_cast<std::size_t>(c)],
                        p0[static_cast<std::size_t>(c)] + (*spec.initial_velocity_m_per_s)[c] * t + 0.5 * g[c] * t * t, 1e-12);
            EXPECT_NEAR(d.point_data.at("v_mps").values.at(static_cast<std::size_t>(c)), v[c], 1e-12);
        }
        EXPECT_EQ(d.point_data.at("shot").values, std::vector<double>{0.0});
        EXPECT_EQ(d.point_data.at("shot").type, "long long");
        EXPECT_NEAR(d.point_data.at("speed_mps").values.at(0), v.norm(), 1e-12);
        EXPECT_EQ(d.point_data.at("shot_diameter_m").values, std::vector<double>{2e-3});
        EXPECT_EQ(d.field_data.size(), 1u);  // the plate stands still: no pose to give
    }
}

INSTANTIATE_TEST_SUITE_P(Schemes, ShotSeriesFlight, ::testing::Values("event", "step"));

TEST(ShotSeries, FieldDataGivesTheMovingComponentsPoses) {
    TestSceneSpec spec = testing::thrown_shot_scene(8, 0.05);
    spec.scheme = "event";
    const double omega = 100.0;  // rad/s
    spec.part = testing::turning_plate_part(omega);
    const TestScene scene(spec);
    const std::string out = scene.make_subdirectory("run");
    // 10.01 ms: the sonotrode at a new phase every step (20 kHz: 200.2 cycles a step).
    const auto r = testing::run_in_process({scene.scene_path(), out, false, false, {}, {"output.shot_positions=10.01 ms"}});
    ASSERT_EQ(r.code, kExitOk) << r.err;
    const std::vector<testing::VtkReadStep> steps = testing::read_pvd_with_vtk(out + "/paraview/shots.pvd");
    ASSERT_EQ(steps.size(), 5u);
    for (std::size_t k = 0; k < steps.size(); ++k) {
        SCOPED_TRACE("step " + std::to_string(k));
        const long double t = static_cast<long double>(k) * 0.01001L;
        const long double cycles = t * 20e3L;
        const long double phase = 2.0L * M_PIl * (cycles - std::floor(cycles));
        EXPECT_NEAR(steps[k].data.field_numbers("sonotrode_displacement_m").at(0), static_cast<double>(25e-6L * std::sin(phase)), 1e-16);
        const long double turns = omega * t / (2.0L * M_PIl);
        EXPECT_NEAR(steps[k].data.field_numbers("part_angle_rad").at(0), static_cast<double>(2.0L * M_PIl * (turns - std::floor(turns))),
                    1e-12);
        EXPECT_EQ(steps[k].data.points, 8u);
        for (std::size_t i = 0; i < 8; ++i) {
            const double* v = &steps[k].data.point_data.at("v_mps").values[3 * i];
            EXPECT_DOUBLE_EQ(steps[k].data.point_data.at("speed_mps").values[i], std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
        }
    }
}

// The event scheme stops at each step's time; where it stops never changes the run.
TEST(ShotSeries, PausingForItChangesNoImpact) {
    TempDir dir;
    const std::vector<std::string> base = {"process.duration=0.5"};
    std::vector<std::string> with = base;
    with.push_back("output.shot_positions=5 ms");
    ASSERT_EQ(testing::run_in_process({kGear, (dir.path / "plain").string(), false, false, {}, base}).code, kExitOk);
    const auto r = testing::run_in_process({kGear, (dir.path / "series").string(), false, false, {}, with});
    ASSERT_EQ(r.code, kExitOk) << r.err;
    const std::string plain = testing::read_file(dir.path / "plain" / "impacts.csv");
    EXPECT_GT(std::count(plain.begin(), plain.end(), '\n'), 100);
    EXPECT_EQ(testing::read_file(dir.path / "series" / "impacts.csv"), plain);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path / "series" / "paraview" / "shots"), fs::directory_iterator{}), 101);
}

// Interrupted, then resumed: the series continues with no step missing or twice, and ends with
// exactly the files of the run that was never stopped; also when a killed session left steps
// (and a .pvd) written after its last checkpoint, which the resumed run writes again.
class ShotSeriesResume : public ::testing::TestWithParam<const char*> {};

TEST_P(ShotSeriesResume, EndsWithTheUninterruptedRunsFiles) {
    TestSceneSpec spec = testing::small_rod_scene(GetParam(), 0.3);
    const TestScene scene(spec);
    const std::vector<std::string> overrides = {"output.shot_positions=7 ms"};
    const std::string whole = scene.make_subdirectory("whole");
    ASSERT_EQ(testing::run_in_process({scene.scene_path(), whole, false, false, {}, overrides}).code, kExitOk);
    const std::map<std::string, std::string> expected = files_under(fs::path(whole) / "paraview");
    ASSERT_EQ(expected.size(), 1u + 43u + 1u + 3u);  // the .pvd, steps 0..42 (t <= 0.3 s), the .vtm and 3 blocks

    const std::string resumed = scene.make_subdirectory("resumed");
    const auto first = testing::run_in_process({scene.scene_path(), resumed, false, false, 40, overrides});
    ASSERT_EQ(first.code, kExitInterrupted) << first.err;
    const std::vector<testing::VtkReadStep> listed = testing::read_pvd_with_vtk(resumed + "/paraview/shots.pvd");
    ASSERT_GE(listed.size(), 1u);
    ASSERT_LT(listed.size(), 43u);
    for (std::size_t k = 0; k < listed.size(); ++k) {
        EXPECT_EQ(listed[k].time_s, static_cast<double>(k) * 0.007);
        EXPECT_EQ(testing::read_file(fs::path(resumed) / "paraview" / listed[k].file), expected.at(listed[k].file));
    }
    // What a session killed after that checkpoint would leave: the next steps written (here with
    // wrong bytes), and a .pvd that lists them.
    const std::size_t next = listed.size();
    for (std::size_t k = next; k < next + 3; ++k) {
        char name[64];
        std::snprintf(name, sizeof name, "shots/shots_%06zu.vtp", k);
        std::ofstream(fs::path(resumed) / "paraview" / name) << "a step of a killed session";
    }
    std::ofstream(fs::path(resumed) / "paraview" / "shots.pvd") << "a .pvd of a killed session";

    const auto second = testing::run_in_process({scene.scene_path(), resumed, true, false, {}, overrides});
    ASSERT_EQ(second.code, kExitOk) << second.err;
    const std::map<std::string, std::string> got = files_under(fs::path(resumed) / "paraview");
    EXPECT_EQ(got.size(), expected.size());
    for (const auto& [name, bytes] : expected) EXPECT_TRUE(got.count(name) && got.at(name) == bytes) << name << " differs";
    EXPECT_EQ(testing::read_file(fs::path(resumed) / "impacts.csv"), testing::read_file(fs::path(whole) / "impacts.csv"));
}

INSTANTIATE_TEST_SUITE_P(Schemes, ShotSeriesResume, ::testing::Values("event", "step"));

TEST(ShotSeries, AResumeWithAnotherIntervalIsRefused) {
    TestSceneSpec spec = testing::small_rod_scene("step", 0.1);
    const TestScene scene(spec);
    const std::string out = scene.make_subdirectory("run");
    ASSERT_EQ(testing::run_in_process({scene.scene_path(), out, false, false, 20, {"output.shot_positions=7 ms"}}).code, kExitInterrupted);
    const auto again = testing::run_in_process({scene.scene_path(), out, true, false, {}, {"output.shot_positions=5 ms"}});
    EXPECT_EQ(again.code, kExitInputError) << again.err;
}

TEST(ShotSeries, TooManyStepsIsAnInputError) {
    TempDir dir;
    const auto r = testing::run_in_process({kGear, dir.path.string(), false, false, {}, {"output.shot_positions=1 us"}});
    EXPECT_EQ(r.code, kExitInputError);
    EXPECT_NE(r.err.find("output.shot_positions: the shot-position series plans 5000000 steps"), std::string::npos) << r.err;
}

// The mean of a per-triangle value over the peened area: each triangle's area times its share
// that coverage counts (a shot can reach it, no excluded region holds it: the coverage curve's
// weights, sample by sample).
double peened_area_mean(const TriangleMesh& mesh, const std::vector<double>& per_triangle, const std::vector<double>& peened) {
    double sum = 0.0, area = 0.0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        if (!(peened[t] > 0.0)) continue;
        const double a = 0.5 * (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0)).norm() * peened[t];
        sum += a * per_triangle[t];
        area += a;
    }
    return sum / area;
}

// The analysis' ParaView files: the coverage series at its times, equal to the coverage curve and
// ending at the part's final coverage; the impact points named and valued as impacts.csv.
TEST(ParaviewAnalysis, CoverageSeriesFollowsTheCoverageCurve) {
    TempDir dir;
    const auto r = testing::run_in_process({kGear, dir.path.string(), false, true, {}, {"process.duration=1", "output.coverage_steps=5"}});
    ASSERT_EQ(r.code, kExitOk) << r.err;
    const fs::path analysis = dir.path / "analysis";
    const auto model = compile_model(parse_scene_file(kGear));
    const TriangleMesh& gear = *model->components[static_cast<std::size_t>(model->component_index("gear"))].mesh;

    const std::vector<testing::VtkReadStep> steps = testing::read_pvd_with_vtk((analysis / "gear_coverage_series.pvd").string());
    ASSERT_EQ(steps.size(), 6u);
    // The coverage curve at its 50 times (the series' times are among them).
    std::map<std::string, double> curve;
    {
        std::ifstream csv(analysis / "gear_coverage.csv");
        std::string line;
        std::getline(csv, line);
        while (std::getline(csv, line)) {
            const auto comma = line.find(',');
            curve[line.substr(0, comma)] = std::stod(line.substr(comma + 1));
        }
    }
    // The last step is the part's final coverage, as gear.vtp has it; every file's names are the CSVs'.
    const testing::VtkReadPolyData fields = testing::read_vtp_with_vtk((analysis / "gear.vtp").string());
    const std::vector<double>& peened = fields.cell_data.at("peened").values;
    const auto peened_mean = [&](const std::vector<double>& v) { return peened_area_mean(gear, v, peened); };
    std::vector<double> previous(gear.triangle_count(), 0.0);
    for (std::size_t j = 0; j < steps.size(); ++j) {
        SCOPED_TRACE("step " + std::to_string(j));
        const testing::VtkReadPolyData& d = steps[j].data;
        EXPECT_DOUBLE_EQ(steps[j].time_s, 0.2 * static_cast<double>(j));
        EXPECT_EQ(d.field_numbers("time_s"), std::vector<double>{steps[j].time_s});
        ASSERT_EQ(d.polys, gear.triangle_count());
        ASSERT_EQ(d.points, gear.vertices.size());
        EXPECT_EQ(d.coordinates.back(),
                  (std::array<double, 3>{gear.vertices.back().x(), gear.vertices.back().y(), gear.vertices.back().z()}));
        EXPECT_EQ(d.cell_array_names, std::vector<std::string>{"coverage"});
        const std::vector<double>& coverage = d.cell_data.at("coverage").values;
        for (std::size_t t = 0; t < coverage.size(); ++t) ASSERT_GE(coverage[t], previous[t]) << "triangle " << t;  // dents only add
        previous = coverage;
        char time[32];
        std::snprintf(time, sizeof time, "%.8g", steps[j].time_s);
        EXPECT_NEAR(peened_mean(coverage), curve.at(time), 1e-6);
    }
    EXPECT_EQ(peened_mean(steps[0].data.cell_data.at("coverage").values), 0.0);
    EXPECT_GT(peened_mean(previous), 0.005);
    EXPECT_EQ(fields.cell_data.at("coverage").values, previous);
    EXPECT_EQ(fields.cell_array_names,
              (std::vector<std::string>{"impacts", "impacts_per_mm2_s", "mean_vn_mps", "max_vn_mps", "energy_J_per_m2", "coverage",
                                        "impacts_per_mm2_s_smoothed", "mean_vn_mps_smoothed", "energy_J_per_m2_smoothed",
                                        "coverage_smoothed", "smoothing_radius_mm", "reachable", "peened", "excluded", "region"}));

    const testing::VtkReadPolyData impacts = testing::read_vtp_with_vtk((analysis / "gear_impacts.vtp").string());
    EXPECT_EQ(impacts.point_array_names, (std::vector<std::string>{"v_in_mps", "vn_in_mps", "time_s"}));
    std::ifstream csv(dir.path / "impacts.csv");
    std::string header, row;
    std::getline(csv, header);
    std::getline(csv, row);
    std::vector<std::string> cells;
    std::stringstream split(row);
    for (std::string cell; std::getline(split, cell, ',');) cells.push_back(cell);
    // time_s,shot,component,triangle,x_m,y_m,z_m,vx_in_mps,vy_in_mps,vz_in_mps,vn_in_mps,...
    ASSERT_EQ(header.rfind("time_s,shot,component,triangle,x_m,y_m,z_m,vx_in_mps,vy_in_mps,vz_in_mps,vn_in_mps,", 0), 0u) << header;
    EXPECT_EQ(impacts.point_data.at("time_s").values.at(0), std::stod(cells[0]));
    EXPECT_EQ(impacts.coordinates.at(0), (std::array<double, 3>{std::stod(cells[4]), std::stod(cells[5]), std::stod(cells[6])}));
    EXPECT_EQ(std::vector<double>(impacts.point_data.at("v_in_mps").values.begin(), impacts.point_data.at("v_in_mps").values.begin() + 3),
              (std::vector<double>{std::stod(cells[7]), std::stod(cells[8]), std::stod(cells[9])}));
    EXPECT_EQ(impacts.point_data.at("vn_in_mps").values.at(0), std::stod(cells[10]));

    // No series asked: none written, and none left from the analysis before.
    const auto again =
        testing::run_in_process({kGear, dir.path.string(), false, true, {}, {"process.duration=0.2", "output.coverage_steps=0"}});
    ASSERT_EQ(again.code, kExitOk) << again.err;
    EXPECT_FALSE(fs::exists(analysis / "gear_coverage_series.pvd"));
    EXPECT_FALSE(fs::exists(analysis / "gear_coverage_series"));
    EXPECT_TRUE(fs::exists(analysis / "open_in_paraview.py"));
}

// "item NAME points N first x y z bounds x0 x1 y0 y1 z0 z1 arrays A B ..." lines of --describe.
struct DescribedItem {
    std::uint64_t points = 0;
    std::array<double, 3> first{};
    std::vector<std::string> arrays;
};

std::map<std::string, DescribedItem> described(const std::string& output) {
    std::map<std::string, DescribedItem> items;
    std::istringstream lines(output);
    std::string line;
    while (std::getline(lines, line)) {
        std::istringstream words(line);
        std::string word, name;
        words >> word;
        if (word != "item") continue;
        DescribedItem item;
        words >> name >> word >> item.points >> word;
        for (double& x : item.first) {
            words >> word;
            x = std::stod(word);
        }
        while (words >> word && word != "arrays") {}
        while (words >> word) item.arrays.push_back(word);
        items[name] = item;
    }
    return items;
}

std::string run_command(const std::string& command, int& status) {
    testing::ShellResult r = testing::run_shell(command);
    status = r.status;
    return std::move(r.output);
}

// `command` run with a virtual X display of its own (pvbatch needs one): Xvfb picks a free display
// number and reports it once it accepts connections (-displayfd), so the command never races its
// start (xvfb-run's fixed wait did, on a loaded machine); it is stopped when the command ends.
std::string with_virtual_display(const std::string& command) {
    return "pidfile=$(mktemp) && "
           "display=$( (Xvfb -displayfd 1 -screen 0 1600x1200x24 -nolisten tcp 2>/dev/null & echo $! > \"$pidfile\") | head -n 1 ) && "
           "DISPLAY=:$display " +
           command +
           "; status=$?; pid=$(cat \"$pidfile\"); kill $pid; "
           // Until it has gone: a server still shutting down removes its display's socket, which
           // the next attempt's server, given the same display number, may already have made.
           "while kill -0 $pid 2>/dev/null; do sleep 0.1; done; rm -f \"$pidfile\"; exit $status";
}

// The width and height a PNG's header declares.
std::pair<int, int> png_size(const fs::path& png) {
    const std::string bytes = testing::read_file(png);
    if (bytes.size() < 24 || bytes.compare(1, 3, "PNG") != 0) return {0, 0};
    auto be32 = [&](std::size_t at) {
        return (static_cast<unsigned char>(bytes[at]) << 24) | (static_cast<unsigned char>(bytes[at + 1]) << 16) |
               (static_cast<unsigned char>(bytes[at + 2]) << 8) | static_cast<unsigned char>(bytes[at + 3]);
    };
    return {be32(16), be32(20)};
}

// An analysis of a window of the run (`analyze --from --to`) writes its series over that window:
// the first step is before any impact it takes, the last its end, as the part's fields.
TEST(ParaviewAnalysis, CoverageSeriesSpansTheAnalysedWindow) {
    TempDir dir;
    const auto r = testing::run_in_process({kGear, dir.path.string(), false, true, {}, {"process.duration=1", "output.coverage_steps=4"}});
    ASSERT_EQ(r.code, kExitOk) << r.err;
    std::ostringstream out, err;
    AnalyzeOptions window;
    window.from_s = 0.4;
    window.to_s = 0.8;
    ASSERT_EQ(analyze_job(dir.path.string(), out, err, window), kExitOk) << err.str();
    const fs::path analysis = dir.path / "analysis";
    const std::vector<testing::VtkReadStep> steps = testing::read_pvd_with_vtk((analysis / "gear_coverage_series.pvd").string());
    ASSERT_EQ(steps.size(), 5u);
    for (std::size_t j = 0; j < steps.size(); ++j) EXPECT_NEAR(steps[j].time_s, 0.4 + 0.1 * static_cast<double>(j), 1e-12) << "step " << j;
    const std::vector<double>& first = steps.front().data.cell_data.at("coverage").values;
    EXPECT_TRUE(std::all_of(first.begin(), first.end(), [](double c) { return c == 0.0; }));
    const testing::VtkReadPolyData fields = testing::read_vtp_with_vtk((analysis / "gear.vtp").string());
    EXPECT_EQ(steps.back().data.cell_data.at("coverage").values, fields.cell_data.at("coverage").values);
    const std::vector<double>& last = steps.back().data.cell_data.at("coverage").values;
    EXPECT_TRUE(std::any_of(last.begin(), last.end(), [](double c) { return c > 0.0; }));
}

// ParaView itself (Debian's paraview: pvbatch, on a virtual X display, Xvfb) runs the script
// the analysis wrote: every item opens with the arrays it is coloured by, the files are posed at
// the animation's time (the turning gear's impact points where its kinematics put them), and a
// frame is rendered to a PNG.
TEST(ParaviewScript, ParaViewOpensTheRunPosedAtATimeAndRendersAFrame) {
    int status = -1;
    const std::string which = run_command("command -v pvbatch && command -v Xvfb", status);
    ASSERT_EQ(status, 0) << "pvbatch or Xvfb is missing (needed to run the ParaView script): install them with "
                            "`apt-get install paraview python3-paraview xvfb` (.ci/install-deps does). "
                         << which;
    TempDir dir;
    const auto r = testing::run_in_process({kRotatingGear,
                                            dir.path.string(),
                                            false,
                                            true,
                                            {},
                                            {"process.duration=0.2", "output.shot_positions=10 ms", "output.coverage_steps=4"}});
    ASSERT_EQ(r.code, kExitOk) << r.err;
    const fs::path script = dir.path / "analysis" / "open_in_paraview.py";
    const fs::path png = dir.path / "view.png";
    const double t = 0.05;  // s: a step of the shot series; the gear has turned 9 deg
    // On a loaded machine ParaView now and then fails to open its connection to the virtual display
    // ("bad X server connection", before the script runs; 1 of 3 pvbatch runs at once here, each
    // with its own Xvfb): the environment, not the script, so it is tried again (at most 5 times).
    std::string output;
    for (int attempt = 0; attempt < 5; ++attempt) {
        output = run_command(
            "cd /tmp && " + with_virtual_display("pvbatch " + script.string() + " --time 0.05 --describe --screenshot " + png.string()),
            status);
        if (output.find("bad X server connection") == std::string::npos) break;
        std::this_thread::sleep_for(std::chrono::seconds(1 << attempt));  // the load that caused it may pass
    }
    ASSERT_EQ(status, 0) << output;
    EXPECT_EQ(output.find("Traceback"), std::string::npos) << output;
    const std::map<std::string, DescribedItem> items = described(output);
    auto has = [&](const std::string& item, const std::string& array) {
        const auto& a = items.at(item).arrays;
        return std::find(a.begin(), a.end(), array) != a.end();
    };
    ASSERT_EQ(items.size(), 6u) << output;
    EXPECT_TRUE(has("chamber", "role")) << output;
    EXPECT_TRUE(has("assembly_parts", "role")) << output;
    EXPECT_TRUE(has("gear_coverage", "coverage")) << output;
    EXPECT_TRUE(has("gear_fields", "impacts_per_mm2_s")) << output;
    EXPECT_TRUE(has("gear_impacts", "vn_in_mps")) << output;
    EXPECT_TRUE(has("shots", "speed_mps") && has("shots", "shot_diameter_m")) << output;

    // The shot series at t is its step 5.
    const std::vector<testing::VtkReadStep> steps = testing::read_pvd_with_vtk((dir.path / "paraview" / "shots.pvd").string());
    ASSERT_EQ(steps.size(), 21u);
    EXPECT_EQ(items.at("shots").points, steps[5].data.points);
    EXPECT_EQ(items.at("shots").first, steps[5].data.coordinates.at(0));
    // The gear's first impact point (in the gear's frame in its file) where the gear's pose at t puts it.
    const auto model = compile_model(parse_scene_file(kRotatingGear));
    const Component& gear = model->components[static_cast<std::size_t>(model->component_index("gear"))];
    const testing::VtkReadPolyData impacts = testing::read_vtp_with_vtk((dir.path / "analysis" / "gear_impacts.vtp").string());
    const auto& p = impacts.coordinates.at(0);
    SimTime at;
    at.advance(t);
    const Vec3 expected = gear.kinematics.pose(at).to_world(Vec3(p[0], p[1], p[2]));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(items.at("gear_impacts").first[static_cast<std::size_t>(c)], expected[c], 1e-12) << output;
    EXPECT_GT((expected - gear.kinematics.pose(SimTime{}).to_world(Vec3(p[0], p[1], p[2]))).norm(), 1e-3);  // it did turn
    // The static chamber stays where the assembly file has it.
    const testing::VtkReadPolyData chamber = testing::read_vtp_with_vtk((dir.path / "paraview" / "assembly" / "chamber.vtp").string());
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(items.at("chamber").first[static_cast<std::size_t>(c)], chamber.coordinates.at(0)[static_cast<std::size_t>(c)], 1e-15);

    EXPECT_EQ(png_size(png), (std::pair<int, int>{1600, 700}));
    EXPECT_GT(fs::file_size(png), 50'000u);  // a picture, not a blank frame (a blank one is ~10 kB)
}

}  // namespace
}  // namespace peensim
