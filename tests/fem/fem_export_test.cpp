// `peensim export-fem`: the block and shot meshes (counts, sets, volumes), the deck's text for a
// known patch, the grouping of impacts into steps, the job on a real rod run (a curved part: the
// tangent plane) and its refusals (exit 2, with the option or file and what was expected); and
// CalculiX run on a single-impact deck (0.58 mm steel shot at 50 m/s onto steel): it must finish,
// the dent it leaves is compared with eq. 10 and the residual stresses its relaxation step prints
// must be those of a single impact; the cost model's counts and export-fem's estimate and warning. Without `ccx` on PATH that test fails,
// it does not skip: CI installs calculix-ccx.
#include <gtest/gtest.h>

#include <algorithm>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "analysis/impact_log_reader.h"
#include "app/fem/export_fem_job.h"
#include "app/run/run_job.h"
#include "contact/dent.h"
#include "fem/block_mesher.h"
#include "fem/ccx_cost.h"
#include "fem/dent_profile.h"
#include "fem/impact_steps.h"
#include "fem/inp_writer.h"
#include "fem/residual_stress.h"
#include "fem/sphere_mesher.h"
#include "support/files.h"
#include "support/run_in_process.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using peensim::testing::read_file;
using peensim::testing::TempDir;
using namespace peensim;

namespace {

int count_of(const std::string& text, const std::string& what) {
    int n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// Ids listed in the data lines after "*NSET, NSET=<name>" (or ELSET).
std::vector<int> set_ids(const std::string& text, const std::string& keyword_line) {
    std::vector<int> ids;
    auto at = text.find(keyword_line + "\n");
    if (at == std::string::npos) return ids;
    std::istringstream in(text.substr(at + keyword_line.size() + 1));
    for (std::string line; std::getline(in, line) && !line.empty() && line[0] != '*';) {
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream f(line);
        for (int id; f >> id;) ids.push_back(id);
    }
    return ids;
}

PatchImpact impact_at(double t, double x, double y, double dent) {
    PatchImpact p;
    p.time_s = t;
    p.point_m = Vec3(x, y, 0.0);
    p.velocity_m_per_s = Vec3(0.0, 0.0, -10.0);
    p.dent_diameter_m = dent;
    return p;
}

}  // namespace

TEST(FemMesh, GradedAxisIsUniformThenGrowsAndEndsExactly) {
    const std::vector<double> xs = graded_axis(1.0, 0.3, 0.1, 1.5);
    ASSERT_GE(xs.size(), 5u);
    EXPECT_DOUBLE_EQ(xs.front(), 0.0);
    EXPECT_DOUBLE_EQ(xs.back(), 1.0);
    for (int i = 1; i <= 3; ++i) EXPECT_NEAR(xs[static_cast<std::size_t>(i)], 0.1 * i, 1e-12);
    for (std::size_t i = 4; i < xs.size(); ++i) EXPECT_GT(xs[i] - xs[i - 1], 0.1 - 1e-12) << i;  // never finer than the fine zone
}

TEST(FemMesh, BlockCountsSetsAndVolume) {
    BlockMeshSpec spec;
    spec.half_width_m = 1e-3;
    spec.depth_m = 1e-3;
    spec.fine_half_width_m = 0.2e-3;
    spec.fine_depth_m = 0.1e-3;
    spec.element_size_m = 0.05e-3;
    spec.growth = 1.5;
    for (bool quarter : {false, true}) {
        spec.quarter = quarter;
        const BlockMesh b = mesh_block(spec);
        const std::size_t nx = b.xs.size(), ny = b.ys.size(), nz = b.zs.size();
        EXPECT_EQ(nx, ny);
        EXPECT_EQ(b.mesh.nodes.size(), nx * ny * nz);
        EXPECT_EQ(b.mesh.elements.size(), (nx - 1) * (ny - 1) * (nz - 1));
        EXPECT_EQ(b.top.size(), nx * ny);
        EXPECT_EQ(b.bottom.size(), nx * ny);
        EXPECT_EQ(b.x_min.size(), ny * nz);
        EXPECT_EQ(b.y_max.size(), nx * nz);
        EXPECT_EQ(b.top_elements.size(), (nx - 1) * (ny - 1));
        // Fine zone: 0.2 mm in 0.05 mm edges each side of the centre (full) or one side (quarter).
        const std::size_t fine_cells = quarter ? 4 : 8;
        for (std::size_t i = 0; i < fine_cells; ++i) {
            const std::size_t i0 = quarter ? i : nx / 2 - 4 + i;
            EXPECT_NEAR(b.xs[i0 + 1] - b.xs[i0], 0.05e-3, 1e-15);
        }
        EXPECT_EQ(b.profile.size(), quarter ? nx : nx / 2 + 1);
        for (int n : b.profile) EXPECT_EQ(b.mesh.nodes[static_cast<std::size_t>(n)].y(), 0.0);
        double volume = 0.0;
        for (const HexElement& e : b.mesh.elements) {
            const double v = hex_volume(b.mesh, e);
            EXPECT_GT(v, 0.0);
            volume += v;
        }
        EXPECT_NEAR(volume, (quarter ? 1.0 : 4.0) * 1e-9, 1e-21);
    }
}

TEST(FemMesh, ShotBallVolumeSurfaceAndSymmetryPlanes) {
    const double r = 0.29e-3;
    for (int n : {8, 12}) {
        for (bool quarter : {false, true}) {
            const SphereMesh s = mesh_sphere(r, n, quarter);
            const std::size_t per_axis = quarter ? static_cast<std::size_t>(n / 2) : static_cast<std::size_t>(n);
            EXPECT_EQ(s.mesh.elements.size(), per_axis * per_axis * static_cast<std::size_t>(n));
            // Full: 6 n^2 faces; quarter: the outer faces that are not on x = 0 or y = 0.
            EXPECT_EQ(s.surface.size(), quarter ? static_cast<std::size_t>(6 * n * n / 4) : static_cast<std::size_t>(6 * n * n));
            double volume = 0.0;
            for (const HexElement& e : s.mesh.elements) {
                const double v = hex_volume(s.mesh, e);
                EXPECT_GT(v, 0.0);
                volume += v;
            }
            const double exact = 4.0 / 3.0 * M_PI * r * r * r / (quarter ? 4.0 : 1.0);
            EXPECT_NEAR(volume / exact, 1.0, 0.02) << n;  // flat faces between surface nodes cut a little off
            EXPECT_EQ(s.mesh.nodes[static_cast<std::size_t>(s.centre_node)].norm(), 0.0);
            for (int k : s.x0) EXPECT_EQ(s.mesh.nodes[static_cast<std::size_t>(k)].x(), 0.0);
            for (const Vec3& p : s.mesh.nodes) EXPECT_LE(p.norm(), r * (1 + 1e-12));
        }
    }
}

TEST(FemDeck, KnownPatchNodesElementsSetsAndSteps) {
    FemDeck d;
    BlockMeshSpec spec{0.6e-3, 0.5e-3, 0.2e-3, 0.1e-3, 0.05e-3, 1.5, false};
    d.block = mesh_block(spec);
    d.shot_mesh = mesh_sphere(0.29e-3, 4, false);
    d.target = {"TARGET", 210e9, 0.3, 7850, 500e6, 1e9};
    d.shot = {"SHOT", 210e9, 0.3, 7800, std::nullopt, 0.0};
    d.contact_stiffness_pa_per_m = 1e16;
    std::vector<PatchImpact> impacts = {impact_at(0.0, 0.0, 0.0, 0.2e-3), impact_at(1e-5, 0.5e-3, 0.0, 0.2e-3),
                                        impact_at(2e-5, 0.1e-3, 0.0, 0.2e-3)};
    const auto groups = group_impacts(impacts, GroupingRule{2.0, 1e-3});
    ASSERT_EQ(groups.size(), 2u);  // the third is within 2 dents of the first
    plan_steps(d, impacts, groups, 0.29e-3, StepTiming{});
    ASSERT_EQ(d.shots.size(), 3u);
    ASSERT_EQ(d.steps.size(), 2u);
    std::ostringstream s;
    write_inp(s, d);
    const std::string text = s.str();
    const std::size_t nb = d.block.mesh.nodes.size(), eb = d.block.mesh.elements.size();
    const std::size_t ns = d.shot_mesh.mesh.nodes.size(), es = d.shot_mesh.mesh.elements.size();
    EXPECT_EQ(count_of(text, "*NODE, NSET="), 4);
    EXPECT_EQ(count_of(text, "*ELEMENT, TYPE=C3D8I, ELSET=EBLOCK\n"), 1);  // the default block brick
    EXPECT_EQ(count_of(text, "*ELEMENT, TYPE=C3D8, ELSET=ESHOT"), 3);
    // Two impact steps and the relaxation: static, the contact removed, every shot held.
    EXPECT_EQ(count_of(text, "*STEP"), 3);
    EXPECT_EQ(count_of(text, "*DYNAMIC, EXPLICIT\n"), 2);  // the default dynamics
    EXPECT_EQ(count_of(text, "*STATIC\n"), 1);
    const std::string relaxation = text.substr(text.rfind("*STEP"));
    EXPECT_NE(relaxation.find("*MODEL CHANGE, TYPE=CONTACT PAIR, REMOVE\nSTOP, SSHOTS\n"), std::string::npos) << relaxation;
    EXPECT_NE(relaxation.find("*BOUNDARY, FIXED\nNSHOT1, 1, 3\nNSHOT2, 1, 3\nNSHOT3, 1, 3\n"), std::string::npos) << relaxation;
    EXPECT_NE(relaxation.find("*EL PRINT, ELSET=EAXIS\nS, PEEQ\n"), std::string::npos) << relaxation;
    EXPECT_NE(relaxation.find("*NODE PRINT, NSET=NPROFILE\nU\n"), std::string::npos) << relaxation;
    // EAXIS: one element per layer, the column whose corner is the centre, top first.
    const auto axis = set_ids(text, "*ELSET, ELSET=EAXIS");
    ASSERT_EQ(axis.size(), d.block.zs.size() - 1);
    for (std::size_t k = 0; k < axis.size(); ++k) {
        const HexElement& e = d.block.mesh.elements[static_cast<std::size_t>(axis[k] - 1)];
        const Vec3& lo = d.block.mesh.nodes[static_cast<std::size_t>(e[0])];
        EXPECT_EQ(lo.x(), 0.0);
        EXPECT_EQ(lo.y(), 0.0);
        EXPECT_EQ(d.block.mesh.nodes[static_cast<std::size_t>(e[6])].z(), d.block.zs[d.block.zs.size() - 1 - k]);
    }
    d.block_element = FemElement::C3D8R;
    std::ostringstream reduced;
    write_inp(reduced, d);
    EXPECT_EQ(count_of(reduced.str(), "*ELEMENT, TYPE=C3D8R, ELSET=EBLOCK\n"), 1);
    d.explicit_dynamics = false;
    std::ostringstream implicit;
    write_inp(implicit, d);
    EXPECT_EQ(count_of(implicit.str(), "*DYNAMIC, ALPHA=-0.3\n"), 2);
    EXPECT_EQ(count_of(implicit.str(), "EXPLICIT"), 0);
    EXPECT_EQ(set_ids(text, "*NSET, NSET=NTOP").size(), d.block.top.size());
    EXPECT_EQ(set_ids(text, "*NSET, NSET=NBOTTOM").size(), d.block.bottom.size());
    EXPECT_EQ(set_ids(text, "*ELSET, ELSET=ETOP").size(), d.block.top_elements.size());
    EXPECT_EQ(set_ids(text, "*ELSET, ELSET=ESHOTS").size(), 3 * es);
    const auto centres = set_ids(text, "*NSET, NSET=NSHOTCENTRES");
    ASSERT_EQ(centres.size(), 3u);
    EXPECT_EQ(centres[2], static_cast<int>(nb + 2 * ns) + d.shot_mesh.centre_node + 1);
    // Element and node ids run on without gaps, the block first, then the shots.
    std::vector<int> element_ids, node_ids;
    {
        std::istringstream lines(text);
        std::vector<int>* into = nullptr;
        for (std::string line; std::getline(lines, line);) {
            if (line.rfind("**", 0) == 0) continue;
            if (line[0] == '*') {
                into = line.rfind("*ELEMENT", 0) == 0 ? &element_ids : line.rfind("*NODE, NSET=", 0) == 0 ? &node_ids : nullptr;
                continue;
            }
            if (into) into->push_back(std::stoi(line));
        }
    }
    ASSERT_EQ(element_ids.size(), eb + 3 * es);
    ASSERT_EQ(node_ids.size(), nb + 3 * ns);
    for (std::size_t i = 0; i < element_ids.size(); ++i) EXPECT_EQ(element_ids[i], static_cast<int>(i + 1));
    for (std::size_t i = 0; i < node_ids.size(); ++i) EXPECT_EQ(node_ids[i], static_cast<int>(i + 1));
    EXPECT_NE(text.find("*PLASTIC\n500000000, 0.\n1500000000, 1.\n"), std::string::npos);
    EXPECT_NE(text.find("TYPE=NODE TO SURFACE\nSTOP, SSHOTS\n"), std::string::npos);
    EXPECT_NE(text.find("NSHOT3, 3, -10\n"), std::string::npos);
    // Every number fits CalculiX's 20-character fields.
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("*", 0) == 0) continue;
        std::istringstream f(line);
        for (std::string field; std::getline(f, field, ',');) EXPECT_LE(field.size(), 21u) << line;
    }
    // The second step's shot (the third impact) starts back along its path by its speed times the first step.
    EXPECT_EQ(d.shots[2].step, 1);
    const double back = d.shots[2].start_centre_m.z() - (0.29e-3 + 0.02 * 0.29e-3);
    EXPECT_NEAR(back, 10.0 * d.steps[0].duration_s, 1e-15);
}

TEST(FemGrouping, FarApartAndCloseInTimeShareAStepOtherwiseTimeOrder) {
    const double dent = 0.1e-3;
    std::vector<PatchImpact> impacts = {
        impact_at(0.000, 0.0, 0.0, dent),         // step 1
        impact_at(0.001e-3, 1e-3, 0.0, dent),     // far: step 1
        impact_at(0.002e-3, 0.0, 1e-3, dent),     // far from both: step 1
        impact_at(0.003e-3, 0.15e-3, 0.0, dent),  // 1.5 dents from the first: step 2
        impact_at(0.004e-3, -1e-3, 0.0, dent),    // far from the 4th: step 2
        impact_at(5e-3, 2e-3, 2e-3, dent),        // far but 5 ms later: step 3
    };
    const auto groups = group_impacts(impacts, GroupingRule{2.0, 1e-3});
    ASSERT_EQ(groups.size(), 3u);
    EXPECT_EQ(groups[0], (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(groups[1], (std::vector<int>{3, 4}));
    EXPECT_EQ(groups[2], (std::vector<int>{5}));
    // Exactly two dents apart is not farther than two dents.
    const auto tight = group_impacts({impact_at(0, 0, 0, dent), impact_at(0, 2 * dent, 0, dent)}, GroupingRule{2.0, 1.0});
    EXPECT_EQ(tight.size(), 2u);
    // A larger dent sets the distance.
    const auto big = group_impacts({impact_at(0, 0, 0, dent), impact_at(0, 3 * dent, 0, 2 * dent)}, GroupingRule{2.0, 1.0});
    EXPECT_EQ(big.size(), 2u);
}

TEST(ExportFemJob, BadInputsExitTwoWithWhatWasExpected) {
    TempDir dir;
    auto run = [&](ExportFemOptions o, const std::string& phrase) {
        std::ostringstream out, err;
        if (o.output_dir.empty()) o.output_dir = (dir.path / "deck").string();
        EXPECT_EQ(export_fem_job(o, out, err), kExitInputError) << phrase;
        EXPECT_NE(err.str().find(phrase), std::string::npos) << err.str();
    };
    ExportFemOptions o;
    o.run_dir = (dir.path / "missing").string();
    o.center = "0,0,0";
    run(o, "no such run directory");
    o.run_dir = dir.path.string();
    run(o, "not a peensim run directory (no scene.resolved.yaml)");
    ExportFemOptions s;
    s.single = "0,0,0,0,0,-50 m/s";
    run(s, "--shot-diameter: expected the shot diameter");
    s.shot_diameter = "0.58 mm";
    s.single = "0,0,0,0,-50 m/s";
    run(s, "--single: expected x,y,z,vx,vy,vz");
    s.single = "0,0,0,0,0,50 m/s";
    run(s, "must point into the surface");
    s.single = "0,0,0,0,0,-50 kHz";
    run(s, "--single: ");
    s.single = "0,0,0,1 m/s,0,-50 m/s";
    s.quarter = true;
    run(s, "--quarter: the quarter model needs exactly one normal impact");
    s.quarter = false;
    s.single = "0,0,0,0,0,-50 m/s";
    s.center = "1 mm, 2 mm";
    run(s, "--center: expected x,y,z");
    s.center = "";
    s.shot_divisions = 7;
    run(s, "--shot-divisions: expected an even number");
    s.shot_divisions = 8;
    s.element = "C3D20";
    run(s, "--element: expected C3D8I, C3D8R or C3D8, got 'C3D20'");
    s.element = "C3D8I";
    s.dynamics = "static";
    run(s, "--dynamics: expected explicit or implicit, got 'static'");
    ExportFemOptions none;
    run(none, "RUNDIR: expected a run directory");
}

TEST(ExportFemJob, RodRunPatchOnTheCurvedPartAndItsRefusals) {
    TempDir dir;
    RunOptions r;
    r.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml";
    r.output_dir = (dir.path / "run").string();
    r.overrides = {"process.duration=0.1"};
    r.progress = false;
    r.analyze = false;
    std::ostringstream rout, rerr;
    ASSERT_EQ(run_job(r, rout, rerr), kExitOk) << rerr.str();
    ImpactLogReader reader((dir.path / "run" / "impacts.csv").string());
    ImpactRow row;
    ASSERT_TRUE(reader.next(row));
    const Vec3 p = row.point_m;
    auto at = [](const Vec3& q) {
        std::ostringstream s;
        s.precision(17);
        s << q.x() << "," << q.y() << "," << q.z();
        return s.str();
    };

    ExportFemOptions o;
    o.run_dir = (dir.path / "run").string();
    o.output_dir = (dir.path / "deck").string();
    o.center = at(p);
    o.max_impacts = 3;
    std::ostringstream out, err;
    ASSERT_EQ(export_fem_job(o, out, err), kExitOk) << err.str();
    const std::string deck = read_file((dir.path / "deck" / "patch.inp").string());
    EXPECT_NE(deck.find("** Units: SI throughout (m, kg, s, Pa"), std::string::npos);
    EXPECT_NE(deck.find("tangent plane"), std::string::npos);  // the rod is curved
    const std::string csv = read_file((dir.path / "deck" / "impacts.csv").string());
    const int rows = count_of(csv, "\n") - 1;
    EXPECT_GE(rows, 1);
    EXPECT_LE(rows, 3);
    EXPECT_EQ(count_of(deck, "*INITIAL CONDITIONS, TYPE=VELOCITY"), 1);
    EXPECT_EQ(count_of(deck, "** Shot "), rows);
    EXPECT_NE(read_file((dir.path / "deck" / "README.md").string()).find("ccx -i patch"), std::string::npos);
    // The first logged impact is at the centre: impacts.csv row 1 is in the deck.
    EXPECT_NE(csv.find(",1,"), std::string::npos) << csv;

    auto refused = [&](ExportFemOptions bad, const std::string& phrase) {
        std::ostringstream o2, e2;
        EXPECT_EQ(export_fem_job(bad, o2, e2), kExitInputError) << phrase;
        EXPECT_NE(e2.str().find(phrase), std::string::npos) << e2.str();
    };
    ExportFemOptions far = o;
    far.center = at(p + Vec3(0.0, 0.0, 0.05));
    refused(far, "from the surface of component 'rod'");
    ExportFemOptions region = o;
    region.region = "nowhere";
    refused(region, "has no region 'nowhere'");
    ExportFemOptions comp = o;
    comp.component = "chamber";
    refused(comp, "'chamber' is not a logged component");
    // A run directory whose log has no row: no impact in the patch.
    fs::create_directories(dir.path / "empty");
    fs::copy_file(dir.path / "run" / "scene.resolved.yaml", dir.path / "empty" / "scene.resolved.yaml");
    {
        std::ifstream in(dir.path / "run" / "impacts.csv");
        std::string header;
        std::getline(in, header);
        std::ofstream(dir.path / "empty" / "impacts.csv") << header << "\n";
    }
    ExportFemOptions empty = o;
    empty.run_dir = (dir.path / "empty").string();
    refused(empty, "no impact of component 'rod' within");
}

// The default fine element follows the dents that matter: the patch's 10th-percentile dent
// diameter, at least half the median, over 6 (the smallest dent, an almost resting shot's, set it
// before: the shipped gear's default patch came to 4.45 M elements). Checked against the deck's
// own impacts.csv (its dent_diameter_m column) on 40 impacts of a gear run.
TEST(ExportFemJob, TheDefaultElementFollowsTheDentsThatMatter) {
    TempDir dir;
    peensim::testing::InProcessRun r;
    r.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/gear.yaml";
    r.output_dir = (dir.path / "run").string();
    r.overrides = {"process.duration=2"};
    const peensim::testing::InProcessResult run = peensim::testing::run_in_process(r);
    ASSERT_EQ(run.code, kExitOk) << run.err;
    ExportFemOptions o;
    o.run_dir = (dir.path / "run").string();
    o.output_dir = (dir.path / "deck").string();
    o.region = "tooth-10";  // the tooth facing the sonotrode: the most impacts
    o.max_impacts = 40;
    std::ostringstream out, err;
    ASSERT_EQ(export_fem_job(o, out, err), kExitOk) << err.str();
    std::istringstream csv(read_file((dir.path / "deck" / "impacts.csv").string()));
    std::string line;
    std::getline(csv, line);
    ASSERT_EQ(line.substr(line.rfind(',') + 1), "dent_diameter_m");
    std::vector<double> dents;
    while (std::getline(csv, line)) dents.push_back(std::stod(line.substr(line.rfind(',') + 1)));
    ASSERT_GE(dents.size(), 10u);
    std::sort(dents.begin(), dents.end());
    const auto at = [&](double q) { return dents[static_cast<std::size_t>(q * static_cast<double>(dents.size() - 1))]; };
    const double expected_mm = std::max(at(0.1), 0.5 * at(0.5)) / 6.0 * 1e3;
    const std::string said = out.str();
    const std::size_t fine = said.find("(fine ");
    ASSERT_NE(fine, std::string::npos) << said;
    EXPECT_NEAR(std::stod(said.substr(fine + 6)), expected_mm, 1e-3 * expected_mm) << said;
    EXPECT_GT(expected_mm, dents.front() / 6.0 * 1e3);  // coarser than the smallest dent would make it
}

// A run of a shot mix: the deck has one ball, so the user picks the size whose impacts go in it.
TEST(ExportFemJob, AMixRunExportsTheImpactsOfTheChosenSize) {
    TempDir dir;
    RunOptions r;
    r.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/nozzle-mix.yaml";
    r.output_dir = (dir.path / "run").string();
    r.overrides = {"process.duration=3 ms"};
    r.progress = false;
    r.analyze = false;
    std::ostringstream rout, rerr;
    ASSERT_EQ(run_job(r, rout, rerr), kExitOk) << rerr.str();
    ImpactLogReader reader((dir.path / "run" / "impacts.csv").string());
    ASSERT_TRUE(reader.has_shot_diameter());
    std::vector<double> diameter_of_row{0.0};  // by log row (1-based)
    Vec3 centre = Vec3::Zero();
    bool found = false;
    for (ImpactRow row; reader.next(row);) {
        diameter_of_row.push_back(row.shot_diameter_m);
        if (!found && std::abs(row.shot_diameter_m - 0.6e-3) < 1e-12) centre = row.point_m, found = true;
    }
    ASSERT_TRUE(found);
    ExportFemOptions o;
    o.run_dir = (dir.path / "run").string();
    o.output_dir = (dir.path / "deck").string();
    std::ostringstream c;
    c.precision(17);
    c << centre.x() << "," << centre.y() << "," << centre.z();
    o.center = c.str();
    o.max_impacts = 4;
    std::ostringstream out, err;
    EXPECT_EQ(export_fem_job(o, out, err), kExitInputError);
    EXPECT_NE(err.str().find("the run peened with a shot mix (0.71 mm, 0.6 mm, 0.5 mm, 0.425 mm); expected --shot-diameter"),
              std::string::npos)
        << err.str();
    o.shot_diameter = "0.55 mm";
    std::ostringstream out2, err2;
    EXPECT_EQ(export_fem_job(o, out2, err2), kExitInputError);
    EXPECT_NE(err2.str().find("expected one of the run's sizes"), std::string::npos) << err2.str();
    o.shot_diameter = "600 um";
    std::ostringstream out3, err3;
    ASSERT_EQ(export_fem_job(o, out3, err3), kExitOk) << err3.str();
    EXPECT_NE(read_file((dir.path / "deck" / "patch.inp").string()).find("** Units: SI"), std::string::npos);
    // Every impact of the deck is one of a 0.6 mm shot (its log row says so).
    std::istringstream csv(read_file((dir.path / "deck" / "impacts.csv").string()));
    std::string line;
    std::getline(csv, line);
    int rows = 0;
    while (std::getline(csv, line)) {
        std::istringstream fields(line);
        std::string step, shot, log_row;
        std::getline(fields, step, ',');
        std::getline(fields, shot, ',');
        std::getline(fields, log_row, ',');
        const auto k = static_cast<std::size_t>(std::stoul(log_row));
        ASSERT_LT(k, diameter_of_row.size());
        EXPECT_NEAR(diameter_of_row[k], 0.6e-3, 1e-12) << line;
        ++rows;
    }
    EXPECT_GE(rows, 1);
}

// The hand-off end to end: one 0.58 mm steel shot at 50 m/s onto a steel block (500 MPa, perfectly
// plastic), quarter model, the default deck (C3D8I, explicit impact step, static relaxation); ccx
// must finish, the dent is measured from the relaxed surface profile and the residual stresses
// from the EAXIS column.
TEST(ExportFemCalculix, SingleImpactRunsAndLeavesTheDentOfEq10) {
    ASSERT_EQ(std::system("command -v ccx > /dev/null 2>&1"), 0)
        << "ccx (CalculiX, Debian package calculix-ccx) is not on PATH: install it (.ci/install-deps does)";
    TempDir dir;
    ExportFemOptions o;
    o.output_dir = dir.path.string();
    o.single = "0,0,0,0,0,-50 m/s";
    o.shot_diameter = "0.58 mm";
    o.quarter = true;
    // Coarser than the defaults (6 elements a dent, 8 shot divisions: 1152 + 128 elements, ~3 min of
    // ccx): 512 + 54 elements run in ~1 min and still put the dent within a third of eq. 10 and the
    // residual stresses where they belong; the defaults' convergence is the user guide's ("FEM hand-off").
    o.elements_per_dent = 4.0;
    o.shot_divisions = 6;
    std::ostringstream out, err;
    ASSERT_EQ(export_fem_job(o, out, err), kExitOk) << err.str();
    const auto start = std::chrono::steady_clock::now();
    const std::string cmd = "cd '" + dir.path.string() + "' && OMP_NUM_THREADS=1 timeout 600 nice ccx -i patch > ccx.log 2>&1";
    const int rc = std::system(cmd.c_str());
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string log = read_file((dir.path / "ccx.log").string());
    ASSERT_EQ(rc, 0) << log.substr(log.size() > 3000 ? log.size() - 3000 : 0);
    EXPECT_NE(log.find("Job finished"), std::string::npos);
    ASSERT_TRUE(fs::exists(dir.path / "patch.frd"));
    const fs::path dat = dir.path / "patch.dat";
    ASSERT_TRUE(fs::exists(dat));

    const auto nodes = read_inp_nodes((dir.path / "patch.inp").string());
    const auto u = read_dat_last_table(dat.string(), "displacements", "NPROFILE");
    const auto v = read_dat_last_table(dat.string(), "velocities", "NSHOTCENTRES");
    ASSERT_GE(u.size(), 5u);
    ASSERT_EQ(v.size(), 1u);
    std::vector<Vec3> points, displacements;
    for (const auto& [id, d] : u) {
        points.push_back(nodes.at(id));
        displacements.push_back(d);
    }
    const DentProfile dent = dent_profile(points, displacements);
    const double eq10 = dent_diameter(0.58e-3, 7850.0, 50.0, 500e6);
    const double rebound = v.begin()->second.z();
    std::cout << "ccx wall time " << wall << " s; dent: depth " << dent.depth_m * 1e6 << " um, diameter at zero "
              << dent.zero_diameter_m * 1e3 << " mm, pile-up crest diameter " << dent.crest_diameter_m * 1e3 << " mm (height "
              << dent.crest_height_m * 1e6 << " um); eq. 10: " << eq10 * 1e3 << " mm (" << 100.0 * (dent.zero_diameter_m / eq10 - 1.0)
              << " %); rebound " << rebound << " m/s (CoR " << rebound / 50.0 << ")\n";
    // A dent, not noise: deeper than a micrometre, its rim within a third of eq. 10, and the shot
    // bounced back slower than it came.
    EXPECT_GT(dent.depth_m, 1e-6);
    EXPECT_NEAR(dent.zero_diameter_m / eq10, 1.0, 0.33);
    EXPECT_GT(rebound, 0.0);
    EXPECT_LT(rebound, 50.0);

    // The residual stresses under the dent, printed by the relaxation step (static, shot gone):
    // compressive near the surface, of the order of the yield stress (a single impact's field is
    // about -0.5 to -1.5 yield; before the relaxation step the deck wrote -4.4 yield hydrostatic at
    // 220 um), and fading with depth.
    const double yield = 500e6;
    const auto sigma = read_axis_residual_stress((dir.path / "patch.inp").string(), dat.string());
    ASSERT_GE(sigma.size(), 5u);
    double most_compressive = 0.0, largest_mean = 0.0;
    for (const ResidualStressPoint& p : sigma) {
        std::cout << "  depth " << p.depth_m * 1e6 << " um: sxx " << p.sxx_pa / 1e6 << " MPa, szz " << p.szz_pa / 1e6 << " MPa\n";
        if (p.depth_m < eq10) most_compressive = std::min(most_compressive, p.sxx_pa);
        largest_mean = std::max(largest_mean, std::abs(p.sxx_pa + p.syy_pa + p.szz_pa) / 3.0);
        if (p.depth_m > 2.0 * eq10) {
            EXPECT_LT(std::abs(p.sxx_pa), 0.25 * yield) << p.depth_m;  // far below: almost nothing
        }
        EXPECT_NEAR(p.sxx_pa, p.syy_pa, 0.1 * yield) << p.depth_m;  // the quarter's column is symmetric in x and y
    }
    EXPECT_LT(most_compressive, -0.5 * yield);
    EXPECT_GT(most_compressive, -2.0 * yield);
    EXPECT_LT(largest_mean, 1.5 * yield);
}

// The cost model counts what the deck holds: its nodes (block and every shot) and the increments
// its dynamic steps plan (explicit: duration over the stable increment; implicit: over the largest
// increment; rounded up); more nodes cost more time and memory.
TEST(FemCost, EstimateCountsTheDecksNodesAndPlannedIncrements) {
    FemDeck d;
    d.block = mesh_block(BlockMeshSpec{0.6e-3, 0.5e-3, 0.2e-3, 0.1e-3, 0.05e-3, 1.5, false});
    d.shot_mesh = mesh_sphere(0.29e-3, 4, false);
    d.shots.resize(3);
    d.target = {"TARGET", 210e9, 0.3, 7850, 500e6, 0.0};
    d.shot = {"SHOT", 210e9, 0.3, 7850, std::nullopt, 0.0};
    d.steps = {FemStep{1.0e-6, 1e-8, 1e-7, {0}}, FemStep{2.05e-6, 1e-8, 1e-7, {1, 2}}};
    // Explicit (the default): each step over the stable increment, the shortest edge (here the
    // block's 0.05 mm, shorter than the 4-division ball's) over the dilatational wave speed.
    const double c_d = std::sqrt(210e9 * 0.7 / (7850 * 1.3 * 0.4));  // m/s
    EXPECT_NEAR(stable_increment(d), 0.05e-3 / c_d, 1e-9 * 0.05e-3 / c_d);
    EXPECT_EQ(estimate_ccx_cost(d).planned_increments, std::ceil(1.0e-6 / stable_increment(d)) + std::ceil(2.05e-6 / stable_increment(d)));
    // Implicit: each step over its largest increment.
    d.explicit_dynamics = false;
    const CcxCostEstimate c = estimate_ccx_cost(d);
    EXPECT_EQ(c.nodes, static_cast<double>(d.block.mesh.nodes.size() + 3 * d.shot_mesh.mesh.nodes.size()));
    EXPECT_EQ(c.planned_increments, 10.0 + 21.0);
    EXPECT_GT(c.seconds, 0.0);
    EXPECT_GT(c.bytes, 0.0);
    FemDeck bigger = d;
    bigger.block = mesh_block(BlockMeshSpec{0.6e-3, 0.5e-3, 0.2e-3, 0.1e-3, 0.025e-3, 1.5, false});
    const CcxCostEstimate b = estimate_ccx_cost(bigger);
    EXPECT_GT(b.seconds, c.seconds);
    EXPECT_GT(b.bytes, c.bytes);
    FemDeck longer = d;
    longer.steps.push_back(FemStep{1e-6, 1e-8, 1e-7, {}});
    EXPECT_NEAR(estimate_ccx_cost(longer).seconds / c.seconds, 41.0 / 31.0, 1e-12);  // time goes with the increments
}

// export-fem says what CalculiX will take before it writes, and warns (still writing) when that is
// more than an hour or 8 GB on one core.
TEST(ExportFemJob, PrintsTheCalculixEstimateAndWarnsWhenImpractical) {
    TempDir dir;
    ExportFemOptions o;
    o.output_dir = (dir.path / "small").string();
    o.single = "0,0,0,0,0,-50 m/s";
    o.shot_diameter = "0.58 mm";
    o.quarter = true;
    std::ostringstream out, err;
    ASSERT_EQ(export_fem_job(o, out, err), kExitOk) << err.str();
    EXPECT_NE(out.str().find("block 1152 C3D8I elements"), std::string::npos) << out.str();
    EXPECT_NE(out.str().find("  CalculiX estimate: "), std::string::npos) << out.str();
    EXPECT_NE(out.str().find(" planned increments; one core, the cost model of docs/user-guide.md, \"FEM hand-off\")"), std::string::npos)
        << out.str();
    EXPECT_LT(out.str().find("CalculiX estimate"), out.str().find("deck: "));
    EXPECT_EQ(err.str().find("warning"), std::string::npos) << err.str();
    const std::string readme = read_file((dir.path / "small" / "README.md").string());
    EXPECT_NE(readme.find("Expect about "), std::string::npos) << readme;
    EXPECT_NE(readme.find(" GB on one core (1746 nodes, "), std::string::npos) << readme;

    ExportFemOptions big = o;
    big.output_dir = (dir.path / "big").string();
    big.quarter = false;
    big.element_size = "12 um";
    std::ostringstream out2, err2;
    ASSERT_EQ(export_fem_job(big, out2, err2), kExitOk) << err2.str();
    EXPECT_NE(err2.str().find("warning: this deck is impractical for CalculiX on one core: about "), std::string::npos) << err2.str();
    EXPECT_NE(err2.str().find("estimated (more than 60 min or 8.00 GB); fewer --impacts, a larger --element-size"), std::string::npos)
        << err2.str();
    EXPECT_NE(err2.str().find("it is written all the same"), std::string::npos) << err2.str();
    EXPECT_TRUE(fs::exists(dir.path / "big" / "patch.inp"));
}
