// STEP and IGES parts (geometry/cad_reader.h, through load_mesh): solids built and written with
// OpenCASCADE here (a cylinder, a box with a drilled hole; STEP in mm and in inches, IGES as a
// solid and as loose trimmed surfaces) come back closed, outward, in metres from the file's own
// unit, within the volume and area the chordal tolerance allows, finer with a finer tolerance;
// bad files are InputErrors naming the file; a scene with a STEP part passes `check` and runs.
// Built without OpenCASCADE, the one test left checks the message that says what to install.
#include <sys/wait.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "common/input_error.h"
#include "geometry/cad_reader.h"
#include "geometry/mesh_checks.h"
#include "geometry/mesh_loader.h"
#include "scene/schema_defaults.h"
#include "support/shell_command.h"
#include "support/temp_dir.h"

#if PEENSIM_HAVE_OCCT
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <gp_Pln.hxx>

#include <algorithm>
#include <set>
#include <vector>

#include "app/check/check_job.h"
#include "app/exit_codes.h"
#include "support/mesh_error.h"
#include "support/run_in_process.h"
#endif

namespace peensim {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

std::string error_of(const std::string& file, const Tessellation& tessellation = {}) {
    return testing::mesh_error_of(file, [&] { load_mesh(file, MeshFileOptions{1.0, tessellation}); });
}

// The scene's defaults (schema.cpp) are the reader's (a `new` or `check` of a bare file uses them).
TEST(CadReader, SchemaDefaultsAreTheReadersDefaults) {
    EXPECT_DOUBLE_EQ(schema_default_quantity("components[].tessellation.chordal"), Tessellation{}.chordal_m);
    EXPECT_DOUBLE_EQ(schema_default_quantity("components[].tessellation.angular"), Tessellation{}.angular_rad);
}

#if !PEENSIM_HAVE_OCCT

// This build has no OpenCASCADE: a STEP part says what to install (exit 2 from the commands).
TEST(CadReader, WithoutOpenCascadeSaysWhatToInstall) {
    EXPECT_FALSE(cad_reading_available());
    testing::TempDir dir;
    const std::string step = (dir.path / "part.step").string();
    std::ofstream(step) << "ISO-10303-21;\nEND-ISO-10303-21;\n";
    const std::string message = error_of(step);
    EXPECT_NE(message.find("needs OpenCASCADE"), std::string::npos) << message;
    EXPECT_NE(message.find("apt-get install libocct-data-exchange-dev libocct-modeling-algorithms-dev"), std::string::npos) << message;
}

#else

// OpenCASCADE's writers report on stdout; the tests keep it quiet while they write.
struct QuietOpenCascade {
    Handle(Message_Messenger) messenger = Message::DefaultMessenger();
    Message_SequenceOfPrinters saved = messenger->Printers();
    QuietOpenCascade() { messenger->ChangePrinters().Clear(); }
    ~QuietOpenCascade() { messenger->ChangePrinters() = saved; }
};

// write.step.unit is a process-wide setting of OpenCASCADE: set for one write, then put back. It
// must be set before the writer is made: OpenCASCADE 7.6 converts the coordinates with the unit
// of the writer's construction but declares the unit of the moment of writing (set in between, a
// file declares inches and holds millimetre values: read as such, 25.4 times too large).
void write_step(const TopoDS_Shape& shape, const std::string& path, const char* unit = "MM") {
    QuietOpenCascade quiet;
    STEPControl_Controller::Init();  // registers the STEP settings
    const std::string before = Interface_Static::CVal("write.step.unit");
    ASSERT_TRUE(Interface_Static::SetCVal("write.step.unit", unit));
    bool transferred = false, written = false;
    {
        STEPControl_Writer writer;
        transferred = writer.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone;
        written = writer.Write(path.c_str()) == IFSelect_RetDone;
    }
    Interface_Static::SetCVal("write.step.unit", before.c_str());
    ASSERT_TRUE(transferred && written) << path;
}

// IGES in `unit` ("MM", "IN"); as_solid: B-rep mode (a solid, entity 186), else loose trimmed
// surfaces (entity 144), as most CAD systems write IGES.
void write_iges(const TopoDS_Shape& shape, const std::string& path, const char* unit, bool as_solid) {
    QuietOpenCascade quiet;
    IGESControl_Controller::Init();
    IGESControl_Writer writer(unit, as_solid ? 1 : 0);
    ASSERT_TRUE(writer.AddShape(shape));
    writer.ComputeModel();
    ASSERT_TRUE(writer.Write(path.c_str())) << path;
}

// The rod of scenes/rod.yaml (assets/regenerate.sh): radius 5 mm, 30 mm along y centred on y = 0, its
// axis 20 mm above the floor (mm: OpenCASCADE's modelling unit here).
constexpr double kRodRadius_mm = 5.0, kRodLength_mm = 30.0, kRodAxisZ_mm = 20.0;
TopoDS_Shape rod() {
    return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, -kRodLength_mm / 2, kRodAxisZ_mm), gp_Dir(0, 1, 0)), kRodRadius_mm, kRodLength_mm)
        .Shape();
}

// A 20 x 10 x 5 mm block with a 4 mm hole drilled through it (a boolean cut: 7 faces, the hole's
// face reversed).
constexpr double kHoleRadius_mm = 2.0;
TopoDS_Shape drilled_block() {
    const TopoDS_Shape block = BRepPrimAPI_MakeBox(20.0, 10.0, 5.0).Shape();
    const TopoDS_Shape drill = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(10, 5, -1), gp_Dir(0, 0, 1)), kHoleRadius_mm, 7.0).Shape();
    return BRepAlgoAPI_Cut(block, drill).Shape();
}
const double kBlockVolume_m3 = (20.0 * 10.0 * 5.0 - kPi * kHoleRadius_mm * kHoleRadius_mm * 5.0) * 1e-9;

// Chordal tolerance binding everywhere (the angular one at its loosest), for the bounds below.
Tessellation chordal_only(double chordal_m) { return Tessellation{chordal_m, kPi / 4.0}; }

// The exact cylinder's volume and area, and how far below them a tessellation with sagitta <= s
// may fall. Its nodes lie on the surface, so each circle becomes an inscribed polygon whose
// apothem is at least r - s: the polygon holds the circle of radius r - s and lies inside the circle
// of radius r. Area and perimeter (both monotone for convex sets) lie between the two circles'; so
// the volume between pi (r - s)^2 L and pi r^2 L, the caps' area likewise, the side's between
// 2 pi (r - s) L and 2 pi r L: a relative deficit of at most 1 - (1 - s/r)^2 ~ 2 s / r.
struct CylinderBounds {
    double volume_lo, volume_hi, area_lo, area_hi;  // m3, m3, m2, m2
};
CylinderBounds cylinder_bounds(double r, double length, double s) {
    const double inner = r - s;
    return {kPi * inner * inner * length, kPi * r * r * length, 2.0 * kPi * inner * inner + 2.0 * kPi * inner * length,
            2.0 * kPi * r * r + 2.0 * kPi * r * length};
}

void expect_closed_and_outward(const TriangleMesh& mesh) {
    const EdgeReport edges = edge_report(mesh);
    EXPECT_EQ(edges.boundary_edges, 0u);
    EXPECT_EQ(edges.non_manifold_edges, 0u);
    EXPECT_EQ(edges.misoriented_edges, 0u);
    EXPECT_GT(enclosed_volume(mesh), 0.0);
}

class CadReaderFiles : public ::testing::Test {
protected:
    std::string path(const std::string& name) const { return (dir_.path / name).string(); }
    testing::TempDir dir_;
};

TEST_F(CadReaderFiles, StepCylinderIsClosedOutwardInMetresAndWithinTheChordalBound) {
    write_step(rod(), path("rod.step"));
    ASSERT_TRUE(cad_reading_available());
    const double chordal_m = 0.01e-3;
    const TriangleMesh mesh = load_mesh(path("rod.step"), MeshFileOptions{1.0, chordal_only(chordal_m)});
    expect_closed_and_outward(mesh);
    // Nodes lie on the exact surface: the flat caps are exact, the round extremes within the
    // chordal tolerance inside.
    const Bounds b = bounds(mesh);
    EXPECT_NEAR(b.min_m.y(), -15e-3, 1e-12);
    EXPECT_NEAR(b.max_m.y(), 15e-3, 1e-12);
    for (const double far : {-b.min_m.x(), b.max_m.x(), 20e-3 - b.min_m.z(), b.max_m.z() - 20e-3}) {
        EXPECT_LE(far, 5e-3 + 1e-12);
        EXPECT_GE(far, 5e-3 - chordal_m);
    }
    const CylinderBounds exact = cylinder_bounds(kRodRadius_mm * 1e-3, kRodLength_mm * 1e-3, chordal_m);
    const double volume = enclosed_volume(mesh), area = surface_area(mesh);
    EXPECT_GE(volume, exact.volume_lo);
    EXPECT_LE(volume, exact.volume_hi * (1 + 1e-12));
    EXPECT_GE(area, exact.area_lo);
    EXPECT_LE(area, exact.area_hi * (1 + 1e-12));
    // Facets: the three B-rep faces (side, two caps), all in the one solid's group.
    std::set<int> facets(mesh.source_facet.begin(), mesh.source_facet.end());
    EXPECT_EQ(facets, (std::set<int>{0, 1, 2}));
    ASSERT_EQ(mesh.group_names, std::vector<std::string>{"solid1"});
    EXPECT_EQ(mesh.dropped_degenerate_facets, 0u);
}

TEST_F(CadReaderFiles, FinerChordalToleranceGivesMoreTrianglesAndASmallerError) {
    write_step(rod(), path("rod.step"));
    const double exact = kPi * 25e-6 * 30e-3;  // m3
    std::size_t triangles_before = 0;
    double error_before = 1.0;
    for (double chordal_mm : {0.1, 0.03, 0.01, 0.003}) {
        const TriangleMesh mesh = load_mesh(path("rod.step"), MeshFileOptions{1.0, chordal_only(chordal_mm * 1e-3)});
        const double error = (exact - enclosed_volume(mesh)) / exact;
        SCOPED_TRACE(chordal_mm);
        EXPECT_GT(mesh.triangle_count(), triangles_before);
        EXPECT_LT(error, error_before);
        EXPECT_GT(error, 0.0);                                       // inscribed: always below the exact volume
        EXPECT_LE(error, 2.0 * chordal_mm / kRodRadius_mm + 1e-12);  // the bound above, to first order
        triangles_before = mesh.triangle_count();
        error_before = error;
    }
    // The angular tolerance binds on a small radius: 5 deg gives at least 72 facets around.
    const TriangleMesh coarse_chordal = load_mesh(path("rod.step"), MeshFileOptions{1.0, Tessellation{0.1e-3, 5.0 * kPi / 180.0}});
    EXPECT_GT(coarse_chordal.triangle_count(), load_mesh(path("rod.step"), MeshFileOptions{1.0, chordal_only(0.1e-3)}).triangle_count());
}

TEST_F(CadReaderFiles, InchFileGivesTheSameMeshInMetres) {
    write_step(rod(), path("rod-mm.step"), "MM");
    write_step(rod(), path("rod-in.step"), "INCH");
    // The writer honoured the unit: the file's length unit is the inch, its radius 5 / 25.4.
    std::stringstream text;
    text << std::ifstream(path("rod-in.step")).rdbuf();
    EXPECT_NE(text.str().find("CONVERSION_BASED_UNIT('INCH'"), std::string::npos);
    EXPECT_NE(text.str().find("0.196850393701"), std::string::npos);
    const TriangleMesh mm = load_mesh(path("rod-mm.step"), 1.0);
    const TriangleMesh in = load_mesh(path("rod-in.step"), 1.0);
    // The same triangles (the two files may list the faces in another order): every vertex of one
    // has its twin in the other within the round trip through 25.4, and the same volume and area.
    ASSERT_EQ(in.triangle_count(), mm.triangle_count());
    ASSERT_EQ(in.vertices.size(), mm.vertices.size());
    double farthest = 0.0;  // m
    for (const Vec3& p : in.vertices) {
        double nearest = 1.0;
        for (const Vec3& q : mm.vertices) nearest = std::min(nearest, (p - q).norm());
        farthest = std::max(farthest, nearest);
    }
    EXPECT_LT(farthest, 1e-12);
    EXPECT_NEAR(enclosed_volume(in), enclosed_volume(mm), 1e-9 * enclosed_volume(mm));
    EXPECT_NEAR(surface_area(in), surface_area(mm), 1e-9 * surface_area(mm));
    // mesh_unit does not apply to a CAD file: the file's unit wins, and is named as the file names it.
    EXPECT_EQ(load_mesh(path("rod-in.step"), 1e-3).vertices, in.vertices);
    EXPECT_EQ(in.declared_unit, "INCH");
    EXPECT_EQ(mm.declared_unit, "millimetre");  // OpenCASCADE names an SI unit in lower case
}

TEST_F(CadReaderFiles, DrilledBlockFromStepAndIgesIsClosedOutwardWithTheHoleWithinTheBound) {
    write_step(drilled_block(), path("block.step"));
    write_iges(drilled_block(), path("block-solid.igs"), "IN", true);
    write_iges(drilled_block(), path("block-faces.iges"), "MM", false);
    const double chordal_m = 0.01e-3;
    // The hole is inscribed: it takes away less than the exact cylinder, at most the ring between
    // r - s and r more.
    const double hole_ring_m3 = kPi * (std::pow(kHoleRadius_mm * 1e-3, 2) - std::pow(kHoleRadius_mm * 1e-3 - chordal_m, 2)) * 5e-3;
    for (const std::string name : {"block.step", "block-solid.igs", "block-faces.iges"}) {
        SCOPED_TRACE(name);
        const TriangleMesh mesh = load_mesh(path(name), MeshFileOptions{1.0, chordal_only(chordal_m)});
        expect_closed_and_outward(mesh);
        EXPECT_GE(enclosed_volume(mesh), kBlockVolume_m3 * (1 - 1e-9));
        EXPECT_LE(enclosed_volume(mesh), kBlockVolume_m3 + hole_ring_m3);
        const Bounds b = bounds(mesh);
        EXPECT_NEAR(b.max_m.x(), 20e-3, 1e-9);
        EXPECT_NEAR(b.max_m.y(), 10e-3, 1e-9);
        EXPECT_NEAR(b.max_m.z(), 5e-3, 1e-9);
        std::set<int> facets(mesh.source_facet.begin(), mesh.source_facet.end());
        EXPECT_EQ(facets.size(), 7u);  // 6 planes (2 with a hole) and the hole
        // Loose IGES surfaces are sewn, and the closed shell made a solid.
        EXPECT_EQ(mesh.group_names, std::vector<std::string>{"solid1"});
        EXPECT_EQ(mesh.declared_unit, name == "block.step" ? "millimetre" : name == "block-solid.igs" ? "INCH" : "MM");
    }
}

TEST_F(CadReaderFiles, ASurfaceModelIsReadAsAnOpenSurface) {
    const TopoDS_Shape square = BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 0.0, 10.0, 0.0, 10.0).Shape();
    write_step(square, path("sheet.step"));
    const TriangleMesh mesh = load_mesh(path("sheet.step"), 1.0);
    EXPECT_EQ(mesh.group_names, std::vector<std::string>{"surface"});
    EXPECT_GT(edge_report(mesh).boundary_edges, 0u);
    EXPECT_NEAR(surface_area(mesh), 100e-6, 1e-15);
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) EXPECT_GT(triangle_normal(mesh, t).z(), 0.999);
}

TEST_F(CadReaderFiles, BadFilesAreInputErrorsNamingTheFile) {
    std::ofstream(path("empty.step")).flush();
    std::ofstream(path("garbage.stp")) << "solid not a step file\nfacet normal 0 0 1\n";
    std::ofstream(path("garbage.igs")) << "hello\n";
    std::ofstream(path("empty.IGES")).flush();
    EXPECT_NE(error_of(path("empty.step")).find("the file is empty"), std::string::npos);
    const std::string garbage = error_of(path("garbage.stp"));
    EXPECT_NE(garbage.find("cannot read STEP file (OpenCASCADE: "), std::string::npos) << garbage;
    EXPECT_NE(error_of(path("garbage.igs")).find("IGES file holds no shape"), std::string::npos);
    EXPECT_NE(error_of(path("empty.IGES")).find("the file is empty"), std::string::npos);
    // A STEP file with a curve and no solid or face: nothing to tessellate.
    write_step(BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 0), gp_Pnt(10, 0, 0)).Shape(), path("edge.step"));
    const std::string edge = error_of(path("edge.step"));
    EXPECT_TRUE(edge.find("no solid and no face") != std::string::npos || edge.find("holds no shape") != std::string::npos) << edge;
    // Tolerances must be positive.
    write_step(rod(), path("rod.step"));
    EXPECT_NE(error_of(path("rod.step"), Tessellation{0.0, 0.1}).find("chordal tolerance"), std::string::npos);
    EXPECT_NE(error_of(path("rod.step"), Tessellation{1e-5, -1.0}).find("angular tolerance"), std::string::npos);
}

// The rod scene (scenes/rod.yaml) with its rod a STEP file: `check` passes and a short run logs
// impacts on it.
TEST_F(CadReaderFiles, SceneWithAStepPartChecksAndRuns) {
    write_step(rod(), path("rod.step"));
    const std::string assets = std::string(PEENSIM_SOURCE_DIR) + "/assets/";
    std::ofstream(path("scene.yaml")) << "name: rod from STEP\n"
                                         "process: {duration: 30 ms, seed: 1}\n"
                                         "shot: {count: 200, diameter: 2 mm, material: steel}\n"
                                         "materials:\n"
                                         "  steel: {density: 7.8 g/cm3}\n"
                                         "  copper: {density: 8.96 g/cm3, yield_stress: 70 MPa}\n"
                                         "contacts:\n"
                                         "  default: {C0: 0.9, V0: 0.5 m/s, mu: 0.71, f: 0.1}\n"
                                         "components:\n"
                                         "  - {name: sonotrode, role: sonotrode, mesh: "
                                      << assets
                                      << "rod-sonotrode.stl, mesh_unit: mm, material: steel,\n"
                                         "     vibration: {amplitude: 25 um, frequency: 20 kHz, axis: [0, 0, 1]}}\n"
                                         "  - {name: chamber, role: chamber, mesh: "
                                      << assets
                                      << "rod-chamber.stl, mesh_unit: mm, material: steel}\n"
                                         "  - {name: rod, role: part, mesh: rod.step, material: copper,\n"
                                         "     tessellation: {chordal: 0.02 mm, angular: 10 deg}}\n"
                                         "output: {log: [rod]}\n";
    std::ostringstream out, err;
    ASSERT_EQ(check_job(path("scene.yaml"), {}, true, out, err), kExitOk) << err.str() << out.str();
    EXPECT_NE(out.str().find("closed"), std::string::npos) << out.str();
    // The resolved scene states the tessellation, and no mesh_unit for the STEP part.
    EXPECT_NE(out.str().find("tessellation: {chordal: 2e-05, angular: 0.17453292519943"), std::string::npos) << out.str();

    testing::InProcessRun options;
    options.scene_path = path("scene.yaml");
    options.output_dir = path("out");
    const testing::InProcessResult run = testing::run_in_process(options);
    ASSERT_EQ(run.code, kExitOk) << run.err;
    std::ifstream summary(path("out/summary.json"));
    std::stringstream text;
    text << summary.rdbuf();
    EXPECT_NE(text.str().find("\"rod\""), std::string::npos);
}

// OpenCASCADE's libraries cost every process that links them ~25 ms of start-up: the peensim
// binary does not link them, and loads them (libpeensim_cad.so) when a scene names a STEP part.
TEST_F(CadReaderFiles, ThePeensimBinaryLoadsOpenCascadeOnlyForACadPart) {
    if (std::system("command -v ldd >/dev/null 2>&1") != 0) GTEST_SKIP() << "no ldd";
    const std::string libs = testing::run_shell(std::string("ldd '") + PEENSIM_BINARY + "'").output;
    EXPECT_NE(libs.find("libc.so"), std::string::npos) << libs;
    EXPECT_EQ(libs.find("libTK"), std::string::npos) << libs;
    // The binary reads one all the same: `new` around a STEP rod, then `check` of that scene.
    write_step(rod(), path("rod.step"));
    const std::string binary = std::string("'") + PEENSIM_BINARY + "'";
    const testing::ShellResult made = testing::run_shell(binary + " new '" + path("rod.step") + "' -o '" + path("rod.yaml") + "' 2>&1");
    ASSERT_EQ(made.status, 0) << made.output;
    const testing::ShellResult checked = testing::run_shell(binary + " check '" + path("rod.yaml") + "' 2>&1");
    EXPECT_EQ(checked.status, 0) << checked.output;
    EXPECT_NE(checked.output.find("closed"), std::string::npos) << checked.output;
}

// An installation without the module (the binary alone, its path pointing nowhere) cannot read the
// scene's STEP part, as a build without OpenCASCADE cannot: an input error (exit 2) naming the
// file, what is missing and the way round it.
TEST_F(CadReaderFiles, WithoutTheCadModuleAStepPartIsRefusedAsInput) {
    write_step(rod(), path("rod.step"));
    const std::string binary = std::string("'") + PEENSIM_BINARY + "'";
    const testing::ShellResult made = testing::run_shell(binary + " new '" + path("rod.step") + "' -o '" + path("rod.yaml") + "' 2>&1");
    ASSERT_EQ(made.status, 0) << made.output;
    fs::create_directories(path("alone"));
    fs::copy_file(PEENSIM_BINARY, path("alone/peensim"));
    const testing::ShellResult checked = testing::run_shell("PEENSIM_CAD_MODULE='" + path("nowhere.so") + "' '" + path("alone/peensim") +
                                                            "' check '" + path("rod.yaml") + "' 2>&1");
    ASSERT_TRUE(WIFEXITED(checked.status)) << checked.output;
    EXPECT_EQ(WEXITSTATUS(checked.status), kExitInputError) << checked.output;
    EXPECT_NE(checked.output.find(path("rod.step")), std::string::npos) << checked.output;
    EXPECT_NE(checked.output.find("reading STEP/IGES needs libpeensim_cad.so"), std::string::npos) << checked.output;
    EXPECT_NE(checked.output.find("or export the part as STL"), std::string::npos) << checked.output;
    // Where: the line of the part's `mesh:` field, not of its component's entry.
    std::ifstream scene(path("rod.yaml"));
    int line = 0, mesh_line = 0;
    for (std::string text; std::getline(scene, text);) {
        ++line;
        if (text.find("mesh:") != std::string::npos && text.find("rod.step") != std::string::npos) mesh_line = line;
    }
    ASSERT_GT(mesh_line, 0);
    EXPECT_NE(checked.output.find("rod.yaml:" + std::to_string(mesh_line) + ":"), std::string::npos) << checked.output;
    // A part given by --set is an error there.
    const testing::ShellResult set =
        testing::run_shell("PEENSIM_CAD_MODULE='" + path("nowhere.so") + "' '" + path("alone/peensim") + "' check '" + path("rod.yaml") +
                           "' --set 'components[rod].mesh=" + path("rod.step") + "' 2>&1");
    ASSERT_TRUE(WIFEXITED(set.status)) << set.output;
    EXPECT_EQ(WEXITSTATUS(set.status), kExitInputError) << set.output;
    EXPECT_NE(set.output.find("<--set>"), std::string::npos) << set.output;
    EXPECT_EQ(set.output.find("rod.yaml:"), std::string::npos) << set.output;
}

// A sweep of such a part refuses it before any run starts (every run would refuse it): exit 2 at
// the part's mesh: line, no run folder; a variant that makes a part STEP is blamed on its line.
TEST_F(CadReaderFiles, WithoutTheCadModuleASweepOfAStepPartRefusesItBeforeAnyRun) {
    write_step(rod(), path("rod.step"));
    const std::string binary = std::string("'") + PEENSIM_BINARY + "'";
    ASSERT_EQ(testing::run_shell(binary + " new '" + path("rod.step") + "' -o '" + path("rod.yaml") + "' 2>&1").status, 0);
    fs::create_directories(path("alone"));
    fs::copy_file(PEENSIM_BINARY, path("alone/peensim"));
    const std::string alone = "PEENSIM_CAD_MODULE='" + path("nowhere.so") + "' '" + path("alone/peensim") + "' ";
    const testing::ShellResult swept = testing::run_shell(alone + "sweep '" + path("rod.yaml") + "' -o '" + path("out") +
                                                          "' --vary shot.count=8,16 --set 'process.duration=1 ms' 2>&1");
    ASSERT_TRUE(WIFEXITED(swept.status)) << swept.output;
    EXPECT_EQ(WEXITSTATUS(swept.status), kExitInputError) << swept.output;
    EXPECT_NE(swept.output.find("reading STEP/IGES needs libpeensim_cad.so"), std::string::npos) << swept.output;
    EXPECT_NE(swept.output.find("rod.yaml:"), std::string::npos) << swept.output;
    EXPECT_EQ(swept.output.find("sweep: "), std::string::npos) << swept.output;  // no "sweep: 2 variants x 1 seed = 2 runs"
    EXPECT_FALSE(fs::exists(path("out/count-8"))) << swept.output;
    // The scene with an STL part (never read: the check reads no mesh), one variant a STEP part.
    std::ofstream(path("study.yaml")) << "scene: " << path("rod.yaml") << "\n"
                                      << "set: [\"components[rod].mesh=" << PEENSIM_SOURCE_DIR << "/assets/rod.stl\"]\n"
                                      << "variants:\n"
                                      << "  - {name: stl, set: {shot.count: 8}}\n"
                                      << "  - {name: cad, set: {\"components[rod].mesh\": \"" << path("rod.step") << "\"}}\n";
    const testing::ShellResult listed = testing::run_shell(alone + "sweep '" + path("study.yaml") + "' -o '" + path("out2") + "' 2>&1");
    ASSERT_TRUE(WIFEXITED(listed.status)) << listed.output;
    EXPECT_EQ(WEXITSTATUS(listed.status), kExitInputError) << listed.output;
    EXPECT_NE(listed.output.find("study.yaml:5:"), std::string::npos) << listed.output;
    EXPECT_NE(listed.output.find("reading STEP/IGES needs libpeensim_cad.so"), std::string::npos) << listed.output;
    EXPECT_FALSE(fs::exists(path("out2/stl"))) << listed.output;
    // Where else a part is given: a grid's vary key (its own line, not the first key's), and the
    // sweep file's set (its line: the file has no --set).
    const auto refused_at = [&](const std::string& study, const std::string& where) {
        std::ofstream(path("where.yaml")) << study;
        const testing::ShellResult r = testing::run_shell(alone + "sweep '" + path("where.yaml") + "' -o '" + path("out3") + "' 2>&1");
        EXPECT_TRUE(WIFEXITED(r.status) && WEXITSTATUS(r.status) == kExitInputError) << r.output;
        EXPECT_NE(r.output.find(where), std::string::npos) << where << " in " << r.output;
        EXPECT_NE(r.output.find("reading STEP/IGES needs libpeensim_cad.so"), std::string::npos) << r.output;
    };
    const std::string stl = std::string(PEENSIM_SOURCE_DIR) + "/assets/rod.stl";
    refused_at("scene: " + path("rod.yaml") + "\nset: [\"components[rod].mesh=" + stl + "\"]\nvary:\n  shot.count: [8, 16]\n" +
                   "  \"components[rod].mesh\": [\"" + stl + "\", \"" + path("rod.step") + "\"]\n",
               "where.yaml:5:3: vary.components[rod].mesh: variant 'count-8_mesh-");  // line 4 is shot.count's
    refused_at("scene: " + path("rod.yaml") + "\nset: [\"shot.count=8\", \"components[rod].mesh=" + path("rod.step") +
                   "\"]\nvary: {shot.count: [8, 16]}\n",
               "where.yaml:2:6: set: 'components[rod].mesh=" + path("rod.step") + "'");
    // An optimisation whose variable picks the part: blamed on that variable's line, not on the
    // bound of the first variable, which its check varied.
    fs::copy_file(path("rod.step"), path("rod1.step"));
    fs::copy_file(path("rod.step"), path("rod2.step"));
    std::ofstream(path("study5.yaml")) << "scene: " << path("rod.yaml") << "\nset: [\"components[rod].mesh=" << stl << "\"]\nvariables:\n"
                                       << "  count: {path: shot.count, min: 8, max: 16, start: 8, integer: true}\n"
                                       << "  part: {min: 1, max: 2, start: 1, integer: true, set: {\"components[rod].mesh\": \""
                                       << path("rod{}.step") << "\"}}\n";
    const testing::ShellResult optimised =
        testing::run_shell(alone + "optimise '" + path("study5.yaml") + "' -o '" + path("out5") + "' 2>&1");
    ASSERT_TRUE(WIFEXITED(optimised.status)) << optimised.output;
    EXPECT_EQ(WEXITSTATUS(optimised.status), kExitInputError) << optimised.output;
    EXPECT_NE(optimised.output.find(
                  "study5.yaml:5:3: variables.part.start: variable 'part' at its start (components[rod].mesh=" + path("rod1.step") + "): "),
              std::string::npos)
        << optimised.output;
    EXPECT_EQ(optimised.output.find("check-"), std::string::npos) << optimised.output;
    // A STEP part that every variant replaces is never read: the sweep runs (and without the
    // render module its report says why a picture is missing).
    std::ofstream(path("replaced.yaml")) << "scene: " << path("rod.yaml") << "\nset: [\"process.duration=2 ms\"]\nvariants:\n"
                                         << "  - {name: stl, set: {\"components[rod].mesh\": \"" << stl
                                         << "\", \"components[rod].mesh_unit\": mm}}\n";
    const testing::ShellResult replaced =
        testing::run_shell(alone + "sweep '" + path("replaced.yaml") + "' -o '" + path("out4") + "' 2>&1");
    EXPECT_EQ(replaced.status, 0) << replaced.output;
    EXPECT_TRUE(fs::exists(path("out4/stl/s0/impacts.csv"))) << replaced.output;
}

// A module path the user set is the only one tried: a wrong one is an error that says so, even
// where the right module sits beside the binary (before, that one was loaded without a word).
TEST_F(CadReaderFiles, AWrongCadModulePathIsAnErrorNotAFallBack) {
    write_step(rod(), path("rod.step"));
    const std::string binary = std::string("'") + PEENSIM_BINARY + "'";
    ASSERT_EQ(testing::run_shell(binary + " new '" + path("rod.step") + "' -o '" + path("rod.yaml") + "' 2>&1").status, 0);
    std::ofstream(path("junk.so")) << "not a module\n";
    const testing::ShellResult checked =
        testing::run_shell("PEENSIM_CAD_MODULE='" + path("junk.so") + "' " + binary + " check '" + path("rod.yaml") + "' 2>&1");
    ASSERT_TRUE(WIFEXITED(checked.status)) << checked.output;
    EXPECT_EQ(WEXITSTATUS(checked.status), kExitInputError) << checked.output;
    EXPECT_NE(checked.output.find("which PEENSIM_CAD_MODULE does not name:\n  " + path("junk.so") + ": "), std::string::npos)
        << checked.output;
    EXPECT_NE(checked.output.find("or unset it (peensim then looks beside itself)"), std::string::npos) << checked.output;
    EXPECT_EQ(checked.output.find(path("junk.so") + ": " + path("junk.so")), std::string::npos) << checked.output;  // named once
    // Set to blanks only: said so (dlopen's own words for "  " named no file a reader could see).
    const testing::ShellResult blank = testing::run_shell("PEENSIM_CAD_MODULE='  ' " + binary + " check '" + path("rod.yaml") + "' 2>&1");
    ASSERT_TRUE(WIFEXITED(blank.status)) << blank.output;
    EXPECT_EQ(WEXITSTATUS(blank.status), kExitInputError) << blank.output;
    EXPECT_NE(blank.output.find("PEENSIM_CAD_MODULE is set to blanks only (\"  \"): set it to the module's path, or unset it"),
              std::string::npos)
        << blank.output;
    // Unset, the module beside the binary reads the part.
    EXPECT_EQ(testing::run_shell("env -u PEENSIM_CAD_MODULE " + binary + " check '" + path("rod.yaml") + "' 2>&1").status, 0);
}

#endif

}  // namespace
}  // namespace peensim
