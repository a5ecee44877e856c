// Hostile inputs and faults, round 3 (issue 29): each case a tester reported, run through the
// `peensim` binary as a user would, with the exit code and the phrases its message must hold (and
// what it must not do: write outside -o, create directories, print raw bytes, paste a gnuplot
// error into a report). The run directories they work on are made once for the suite: a short rod
// run (finished), the same interrupted, and a short gear run (regions: teeth, an excluded bore).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "analysis/impact_log_reader.h"
#include "analysis/measured_curve.h"
#include "analysis/regions.h"
#include "fem/patch_frame.h"
#include "geometry/mesh_loader.h"
#include "scene/scene_parser.h"
#include "support/child_process.h"
#include "support/files.h"
#include "support/run_in_process.h"
#include "support/shell_command.h"
#include "support/temp_dir.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

const std::string kScenes = std::string(PEENSIM_SOURCE_DIR) + "/scenes/";

std::string quoted(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

struct Cli {
    int code = -1;
    std::string output;  // stdout and stderr
};

// `peensim ARGS...` (each argument one word), run from `cwd` when given.
Cli peensim(const std::vector<std::string>& args, const fs::path& cwd = {}) {
    std::string command = cwd.empty() ? "" : "cd " + quoted(cwd.string()) + " && ";
    command += quoted(PEENSIM_BINARY);
    for (const std::string& a : args) command += " " + quoted(a);
    const ShellResult r = run_shell(command);
    return {WIFEXITED(r.status) ? WEXITSTATUS(r.status) : -1, r.output};
}

// The exit code and every phrase of the message.
void expect_cli(const Cli& r, int code, const std::vector<std::string>& phrases) {
    EXPECT_EQ(r.code, code) << r.output;
    for (const std::string& p : phrases) EXPECT_NE(r.output.find(p), std::string::npos) << "missing '" << p << "' in:\n" << r.output;
}

std::string point_text(const Vec3& p) {
    std::ostringstream s;
    s.precision(17);
    s << p.x() << "," << p.y() << "," << p.z();
    return s.str();
}

// The run directories, made once: runs take seconds.
struct Runs {
    TempDir dir;
    fs::path rod, rod_interrupted, gear;
    Vec3 rod_impact;  // m, a logged impact point on the rod (component frame)
};

Runs& runs() {
    static const std::unique_ptr<Runs> made = [] {
        auto r = std::make_unique<Runs>();
        r->rod = r->dir.path / "rod";
        r->rod_interrupted = r->dir.path / "rod-interrupted";
        r->gear = r->dir.path / "gear";
        InProcessRun rod;
        rod.scene_path = kScenes + "rod.yaml";
        rod.output_dir = r->rod.string();
        rod.overrides = {"process.duration=0.1"};
        EXPECT_EQ(run_in_process(rod).code, kExitOk);
        InProcessRun stopped = rod;  // interrupted at about half its 0.2 s (time steps: a count of them)
        stopped.output_dir = r->rod_interrupted.string();
        stopped.overrides = {"process.duration=0.2", "accuracy.scheme=step"};
        stopped.stop_after_steps = 2000;
        EXPECT_EQ(run_in_process(stopped).code, kExitInterrupted);
        InProcessRun gear;
        gear.scene_path = kScenes + "gear.yaml";
        gear.output_dir = r->gear.string();
        gear.overrides = {"process.duration=0.5"};
        EXPECT_EQ(run_in_process(gear).code, kExitOk);
        ImpactLogReader reader((r->rod / "impacts.csv").string());
        ImpactRow row;
        EXPECT_TRUE(reader.next(row));
        r->rod_impact = row.point_m;
        return r;
    }();
    return *made;
}

// A copy of a run directory (its files, not its analysis) to damage.
fs::path copy_run(const fs::path& from, const fs::path& to) {
    fs::create_directories(to);
    for (const auto& e : fs::directory_iterator(from))
        if (e.is_regular_file()) fs::copy_file(e.path(), to / e.path().filename(), fs::copy_options::overwrite_existing);
    return to;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
}

std::string joined(const std::vector<std::string>& lines, std::size_t count) {
    std::string s;
    for (std::size_t k = 0; k < count && k < lines.size(); ++k) s += lines[k] + "\n";
    return s;
}

// ---- export-fem ----------------------------------------------------------------------------

// 1. A deck name is a file name inside -o: `../../escaped` wrote /tmp/escaped.inp.
TEST(HostileInputs3, ExportFemNamesStayInsideTheOutputDirectory) {
    Runs& r = runs();
    TempDir out;
    const fs::path deck = out.path / "a" / "b" / "fem";
    const std::vector<std::string> base{"export-fem", r.rod.string(), "-o", deck.string(), "--center", point_text(r.rod_impact)};
    const auto with_name = [&](const std::string& name) {
        std::vector<std::string> a = base;
        a.insert(a.end(), {"--name", name});
        return peensim(a);
    };
    expect_cli(with_name("../../escaped"), 2, {"--name", "expected a file name of letters, digits", "no directory separators"});
    EXPECT_FALSE(fs::exists(out.path / "a" / "escaped.inp"));
    EXPECT_FALSE(fs::exists(deck));  // refused before anything was written
    expect_cli(with_name(""), 2, {"--name", "got an empty name"});
    expect_cli(with_name(".."), 2, {"--name", "(a directory)"});
    expect_cli(with_name("/tmp/absolute"), 2, {"--name", "no directory separators"});
    expect_cli(with_name("a b"), 2, {"--name", "got 'a b'"});
    expect_cli(with_name(std::string(201, 'x')), 2, {"--name", "at most 200 bytes"});
    expect_cli(peensim({"export-fem", r.rod.string(), "-o", deck.string(), "--center", point_text(r.rod_impact), "--impacts", "1", "--name",
                        "patch.v2"}),
               0, {"patch.v2.inp"});
    EXPECT_TRUE(fs::exists(deck / "patch.v2.inp"));
}

// 2. Numbers that mean nothing: a negative window, zero impacts (it exported all), nan, inf.
TEST(HostileInputs3, ExportFemNumbersOutsideTheirRangeAreRefused) {
    Runs& r = runs();
    TempDir out;
    const std::vector<std::string> base{"export-fem", r.rod.string(),          "-o", (out.path / "fem").string(),
                                        "--center",   point_text(r.rod_impact)};
    const auto with = [&](const std::vector<std::string>& extra) {
        std::vector<std::string> a = base;
        a.insert(a.end(), extra.begin(), extra.end());
        return peensim(a);
    };
    expect_cli(with({"--group-window", "-1 ms"}), 2, {"--group-window", "expected a duration > 0, got '-1 ms'"});
    expect_cli(with({"--group-window", "0"}), 2, {"--group-window", "expected a duration > 0"});
    expect_cli(with({"--group-window", "nan"}), 2, {"--group-window", "got 'nan'"});
    expect_cli(with({"--group-window", "inf ms"}), 2, {"--group-window", "got 'inf ms'"});
    expect_cli(with({"--impacts", "0"}), 2, {"--impacts", "expected a count >= 1"});
    expect_cli(with({"--impacts", "-3"}), 2, {"--impacts", "expected a count >= 1"});
    expect_cli(with({"--radius", "-1 mm"}), 2, {"--radius", "expected a length > 0"});
    expect_cli(with({"--element-size", "0 mm"}), 2, {"--element-size", "expected a length > 0"});
    expect_cli(with({"--yield-stress", "nan"}), 2, {"--yield-stress", "got 'nan'"});
    expect_cli(with({"--hardening", "-1 MPa"}), 2, {"--hardening", "expected a stress >= 0"});
    expect_cli(with({"--elements-per-dent", "nan"}), 2, {"--elements-per-dent", "expected a number from 1 to 100"});
    expect_cli(with({"--contact-times", "inf"}), 2, {"--contact-times", "expected a number from 1 to 100"});
    expect_cli(with({"--shot-divisions", "0"}), 2, {"--shot-divisions", "expected an even number"});
    expect_cli(with({"--impacts", "1"}), 0, {"export-fem: 1 impacts"});
}

// 3. --region on a region that is not flat (a gear tooth: flanks, tip, side faces) put the centre
// at its centroid, 2 mm inside the gear, and refused it; the centre is now the point of the
// region's surface nearest its centroid: on the mesh, inside the region.
TEST(HostileInputs3, ExportFemRegionCentreIsOnTheRegionsSurface) {
    Runs& r = runs();
    TempDir out;
    const Cli c = peensim({"export-fem", r.gear.string(), "-o", out.path.string(), "--region", "tooth-0", "--radius", "6 mm", "--impacts",
                           "1", "--element-size", "0.2 mm"});
    expect_cli(c, 0, {"export-fem: 1 impacts"});
    EXPECT_EQ(c.output.find("from the surface"), std::string::npos) << c.output;
    // The deck's header: "In the component frame (m): centre x, y, z".
    const std::string deck = read_file(out.path / "patch.inp");
    const std::string key = "In the component frame (m): centre ";
    const auto at = deck.find(key);
    ASSERT_NE(at, std::string::npos) << deck.substr(0, 2000);
    std::string numbers = deck.substr(at + key.size(), deck.find('\n', at) - at - key.size());
    std::replace(numbers.begin(), numbers.end(), ',', ' ');
    std::istringstream in(numbers);
    Vec3 centre;
    in >> centre.x() >> centre.y() >> centre.z();
    ASSERT_FALSE(in.fail()) << numbers;
    const SceneDescription scene = parse_scene_file((r.gear / "scene.resolved.yaml").string());
    const ComponentDesc& gear = scene.components.front().name == "gear" ? scene.components.front() : scene.components.back();
    ASSERT_EQ(gear.name, "gear");
    const TriangleMesh mesh = load_mesh(gear.mesh_path, gear.mesh_unit_m);
    const SurfacePoint s = closest_surface_point(mesh, centre);
    EXPECT_LT(s.distance_m, 1e-9) << "the centre is off the surface by " << s.distance_m << " m";
    const RegionSet regions(mesh, gear.regions);
    std::size_t tooth = regions.size();
    for (std::size_t k = 0; k < regions.size(); ++k)
        if (regions.name(k) == "tooth-0") tooth = k;
    ASSERT_LT(tooth, regions.size());
    EXPECT_TRUE(regions.contains(tooth, s.point_m, static_cast<std::size_t>(s.triangle)));
}

// ---- almen-fit ---------------------------------------------------------------------------

const std::string kCurve = "time_s,arc_height_mm\n15,0.061\n30,0.101\n60,0.166\n90,0.204\n120,0.219\n180,0.241\n240,0.246\n360,0.252\n";

// 4. --plot into a directory that does not exist created it (and its parents, anywhere). The other
// commands' output files (bench --csv, check --render; trade's below) follow the same rule, checked
// before any work.
TEST(HostileInputs3, OutputFilesGoOnlyIntoDirectoriesThatExist) {
    TempDir dir;
    std::ofstream(dir.path / "a.csv") << kCurve;
    const fs::path missing = dir.path / "nonexistent";
    expect_cli(peensim({"almen-fit", "a.csv", "--plot", (missing / "dir" / "p.png").string()}, dir.path), 2,
               {"--plot", "directory", "does not exist", "peensim creates none"});
    EXPECT_FALSE(fs::exists(missing));
    expect_cli(peensim({"almen-fit", "a.csv", "--json", (missing / "fit.json").string()}, dir.path), 2, {"--json", "does not exist"});
    EXPECT_FALSE(fs::exists(missing));
    expect_cli(peensim({"almen-fit", "a.csv", "--plot", dir.path.string()}, dir.path), 2, {"--plot", "is a directory"});
    expect_cli(peensim({"almen-fit", "a.csv", "--json", "fit.json"}, dir.path), 0, {"Intensity"});
    EXPECT_TRUE(fs::exists(dir.path / "fit.json"));
    expect_cli(peensim({"bench", kScenes + "rod.yaml", "--csv", (missing / "b.csv").string()}), 2, {"--csv", "does not exist"});
    expect_cli(peensim({"check", kScenes + "rod.yaml", "--render", (missing / "c.png").string()}), 2, {"--render", "does not exist"});
    EXPECT_FALSE(fs::exists(missing));
}

// 5. The row limit, checked as the file is read (before any fit). The time a large curve takes is
// the benchmark's (tests/bench/almen_fit_rows.sh), not a test's.
TEST(HostileInputs3, AlmenFitRefusesMoreRowsThanItsLimit) {
    TempDir dir;
    std::ofstream csv(dir.path / "many.csv");
    csv << "time_min,arc_height_mm\n";
    for (std::size_t i = 0; i <= kMaxCurveRows; ++i) csv << 1 + i % 50 << ",0." << 100 + i % 7 << "\n";
    csv.close();
    expect_cli(peensim({"almen-fit", "many.csv"}, dir.path), 2,
               {"many.csv:" + std::to_string(kMaxCurveRows + 2) + ":", "more than 100000 rows", "one row per strip"});
}

// 6. Arc heights falling with exposure were told "already at the plateau: peen shorter".
TEST(HostileInputs3, AlmenFitSaysFallingArcHeightsAreWrongAndWhere) {
    TempDir dir;
    std::ofstream(dir.path / "dec.csv") << "time_min,arc_height_mm\n1,0.30\n2,0.25\n4,0.20\n8,0.15\n8,0.16\n";
    const Cli c = peensim({"almen-fit", "dec.csv"}, dir.path);
    expect_cli(c, 2,
               {"dec.csv:6:", "arc_height_mm", "arc heights must not fall with exposure", "0.3 mm at the shortest exposure, 1 min (line 2)",
                "0.155 mm at the longest, 8 min (lines 5, 6)", "exposure is the first column"});
    EXPECT_EQ(c.output.find("peen strips shorter"), std::string::npos) << c.output;
}

// 7. A binary file printed its bytes; now: the file, the line and column, what was expected, an
// escaped excerpt, and nothing unprintable on the terminal.
TEST(HostileInputs3, AlmenFitOnABinaryFileNamesItWithoutPrintingItsBytes) {
    TempDir dir;
    std::string bytes;
    std::uint32_t x = 12345;
    for (int i = 0; i < 4000; ++i) {
        x = x * 1664525u + 1013904223u;
        bytes += static_cast<char>(x >> 24);
    }
    std::ofstream(dir.path / "random.csv", std::ios::binary) << bytes;
    std::ofstream(dir.path / "late.csv", std::ios::binary) << "time_min,arc_height_mm\n1,0.1\n2,0.\x01\x02\xff"
                                                           << "\n";
    std::ofstream(dir.path / "long.csv", std::ios::binary) << "time_min,arc_height_mm\n1," << std::string(10000, '9') << "\n";
    for (const auto& [file, phrases] : std::vector<std::pair<std::string, std::vector<std::string>>>{
             {"random.csv", {"random.csv:1:"}},
             {"late.csv", {"late.csv:3:5:", "expected a text CSV file", "got the byte 0x01", "'2,0.\\x01\\x02\\xFF'"}},
             {"long.csv", {"long.csv:2:", "a line longer than 4096 bytes", "(4096 bytes)"}}}) {
        const Cli c = peensim({"almen-fit", file}, dir.path);
        expect_cli(c, 2, phrases);
        for (const char ch : c.output) {
            const auto u = static_cast<unsigned char>(ch);
            EXPECT_TRUE(u == '\n' || (u >= 0x20 && u < 0x7f)) << file << ": printed the byte " << int(u) << " in:\n" << c.output;
        }
        EXPECT_LT(c.output.size(), 600u) << c.output;
    }
}

// ---- trade -------------------------------------------------------------------------------

// 8. `--settle nan` ran with the default; nan, inf and negative times are refused before any run.
TEST(HostileInputs3, TradeRefusesTimesAndNumbersThatAreNotOnes) {
    TempDir dir;
    const std::string scene = kScenes + "rod-soft.yaml";
    expect_cli(peensim({"trade", scene, "--settle", "nan"}), 2, {"--settle", "got 'nan'"});
    expect_cli(peensim({"trade", scene, "--settle", "inf"}), 2, {"--settle", "got 'inf'"});
    expect_cli(peensim({"trade", scene, "--settle", "-1 ms"}), 2, {"--settle", "expected a time >= 0, got '-1 ms'"});
    expect_cli(peensim({"trade", scene, "--settle", "1e9 s"}), 2, {"--settle", "expected less than the run's duration"});
    expect_cli(peensim({"trade", scene, "--reference-steps", "nan"}), 2, {"--reference-steps", "expected a number from 20 to 10000"});
    expect_cli(peensim({"trade", scene, "--plot", (dir.path / "no" / "p.png").string()}), 2, {"--plot", "does not exist"});
    expect_cli(peensim({"trade", scene, "--csv", (dir.path / "no" / "t.csv").string()}), 2, {"--csv", "does not exist"});
    EXPECT_FALSE(fs::exists(dir.path / "no"));
}

// ---- analyze -----------------------------------------------------------------------------

// The analysis on any number of cores: the same figures to the byte; no cores is refused.
TEST(HostileInputs3, AnalyzeGivesTheSameFiguresOnOneCoreAsOnSeveral) {
    Runs& r = runs();
    TempDir dir;
    const fs::path one = copy_run(r.rod, dir.path / "one"), three = copy_run(r.rod, dir.path / "three");
    expect_cli(peensim({"analyze", one.string(), "--threads", "1"}), 0, {"analysis:"});
    expect_cli(peensim({"analyze", three.string(), "--threads", "3"}), 0, {"analysis:"});
    const std::string figures = read_file(one / "analysis" / "figures.json");
    EXPECT_NE(figures.find("time_to_target"), std::string::npos);
    EXPECT_EQ(figures, read_file(three / "analysis" / "figures.json"));
    expect_cli(peensim({"analyze", one.string(), "--threads", "0"}), 2, {"--threads"});
    expect_cli(peensim({"run", kScenes + "rod.yaml", "--threads", "-2"}), 2, {"--threads"});
}

// 9. A log cut mid-row was analysed without a word; a NaN row in the middle was dropped without one.
TEST(HostileInputs3, AnalyzeSaysWhereItsLogWasCutAndRefusesDamage) {
    Runs& r = runs();
    TempDir dir;
    const std::vector<std::string> lines = lines_of(read_file(r.rod / "impacts.csv"));
    ASSERT_GT(lines.size(), 102u);
    // Cut inside row 101's text (line 102): the 100 rows before are analysed, with a warning.
    const fs::path cut = copy_run(r.rod, dir.path / "cut");
    std::ofstream(cut / "impacts.csv", std::ios::binary | std::ios::trunc) << joined(lines, 101) << lines[101].substr(0, 40);
    const Cli c = peensim({"analyze", cut.string()});
    expect_cli(c, 0,
               {"warning:", "impacts.csv:102: the impact log ends inside row 101 (line 102): the log was cut", "after the run finished",
                "the 100 rows before it are analysed"});
    EXPECT_NE(read_file(cut / "analysis" / "report.md").find("The impact log ended inside a row"), std::string::npos);
    // The same cut in a killed run's partial log: the warning says so.
    const fs::path killed = copy_run(r.rod, dir.path / "killed");
    fs::remove(killed / "impacts.csv");
    fs::remove(killed / "summary.json");
    std::ofstream(killed / "impacts.csv.partial", std::ios::binary) << joined(lines, 101) << lines[101].substr(0, 40);
    expect_cli(peensim({"analyze", killed.string()}), 0,
               {"impacts.csv.partial:102: the impact log ends inside row 101", "a run killed while writing it"});
    // A NaN in the middle: the line, the column and its name.
    const fs::path nan = copy_run(r.rod, dir.path / "nan");
    std::vector<std::string> damaged = lines;
    std::vector<std::string> fields;
    {
        std::istringstream f(damaged[4]);
        for (std::string x; std::getline(f, x, ',');) fields.push_back(x);
    }
    fields[10] = "nan";  // vn_in_mps
    std::string row;
    for (std::size_t k = 0; k < fields.size(); ++k) row += (k ? "," : "") + fields[k];
    const std::size_t column = row.find(",nan,") + 2;  // 1-based, where "nan" begins
    damaged[4] = row;
    std::ofstream(nan / "impacts.csv", std::ios::binary | std::ios::trunc) << joined(damaged, damaged.size());
    expect_cli(peensim({"analyze", nan.string()}), 2,
               {"impacts.csv:5:" + std::to_string(column) + ": vn_in_mps: malformed impact row 4: expected a finite number, got 'nan'"});
    // Garbage: a field that is no number, binary bytes, a component the run does not log.
    const auto refused = [&](const std::string& name, const std::string& bad_row, const std::vector<std::string>& phrases) {
        const fs::path d = copy_run(r.rod, dir.path / name);
        std::vector<std::string> l = lines;
        l[6] = bad_row;
        std::ofstream(d / "impacts.csv", std::ios::binary | std::ios::trunc) << joined(l, l.size());
        expect_cli(peensim({"analyze", d.string()}), 2, phrases);
    };
    refused("garbage", "0.01,3,rod,12,x,0,0,0,0,0,0,0,0,0,0,0",
            {"impacts.csv:7:", "x_m: malformed impact row 6: expected a number, got 'x'"});
    refused("binary", std::string("0.01,3,rod\x01\x02,12"), {"impacts.csv:7:", "binary data"});
    std::string other = lines[6];
    other.replace(other.find(",rod,"), 5, ",gear,");
    refused("other", other, {"impacts.csv:7: component: malformed impact row 6: expected a component the run logs ('rod'), got 'gear'"});
}

// 10. A killed run (no summary.json) was analysed over the scene's whole duration; and a resumed
// run left the summary of the session before it, which analyze read as the run's.
TEST(HostileInputs3, AnalyzeTakesTheTimeAKilledRunSimulated) {
    Runs& r = runs();
    TempDir dir;
    // The interrupted run's summary says when it stopped; without it (a kill) the checkpoint does.
    const std::string summary = read_file(r.rod_interrupted / "summary.json");
    const auto at = summary.find("\"simulated_time_s\":");
    ASSERT_NE(at, std::string::npos);
    const double stopped_s = std::stod(summary.substr(at + 19));
    ASSERT_GT(stopped_s, 0.0);
    ASSERT_LT(stopped_s, 0.2);
    const fs::path killed = copy_run(r.rod_interrupted, dir.path / "killed");
    fs::remove(killed / "summary.json");
    const Cli c = peensim({"analyze", killed.string()});
    expect_cli(c, 0, {"the run did not finish; analysing the", "no summary.json: the run was killed", "not the scene's 0.2 s"});
    EXPECT_TRUE(c.output.find("from its checkpoint") != std::string::npos ||
                c.output.find("from its last logged impact") != std::string::npos)
        << c.output;
    // Not the scene's 0.2 s: the time it stopped at (its checkpoint's), as its summary had said.
    const std::string report = read_file(killed / "analysis" / "report.md");
    EXPECT_EQ(report.find(", 0.2 s of peening simulated"), std::string::npos) << report.substr(0, 400);
    std::ostringstream stopped;
    stopped << ", " << std::setprecision(4) << stopped_s << " s of peening simulated";
    EXPECT_NE(report.find(stopped.str()), std::string::npos) << stopped.str() << " in " << report.substr(0, 400);
}

TEST(HostileInputs3, AResumedRunNeverLeavesTheSummaryOfTheSessionBefore) {
    TempDir dir;
    const fs::path run = dir.path / "run";
    const std::string scene = kScenes + "rod.yaml";
    // A long run, interrupted: its summary says where it stopped.
    expect_cli(
        peensim({"run", scene, "-o", run.string(), "--set", "process.duration=100", "-q", "--no-render", "--stop-after-steps", "2000"}),
        130, {});
    ASSERT_TRUE(fs::exists(run / "summary.json"));
    // Resumed, and killed once the resumed session has started: no summary of the earlier
    // session may stand (analyze would read its time as the run's).
    ChildProcess child({PEENSIM_BINARY, "run", scene, "-o", run.string(), "--set", "process.duration=100", "-q", "--no-render", "--resume"},
                       (dir.path / "out.txt").string(), (dir.path / "err.txt").string());
    for (int k = 0; k < 600 && fs::exists(run / "summary.json"); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_FALSE(fs::exists(run / "summary.json")) << read_file(dir.path / "err.txt");
    child.signal(SIGKILL);
    child.wait_exit(30.0);
    EXPECT_FALSE(fs::exists(run / "summary.json"));
    expect_cli(peensim({"analyze", run.string()}), 0, {"the run did not finish; analysing the", "no summary.json: the run was killed"});
}

// 11. Every facet excluded: gnuplot's "No valid data points" was pasted into report.md.
TEST(HostileInputs3, AnalyzeOfAPartWithEveryFacetExcludedSaysSoInWords) {
    Runs& r = runs();
    TempDir dir;
    const fs::path all = copy_run(r.gear, dir.path / "all-excluded");
    std::string scene = read_file(all / "scene.resolved.yaml");
    const std::string bore = "max: 0.00501}, exclude: true}";
    ASSERT_NE(scene.find(bore), std::string::npos);
    scene.replace(scene.find(bore), bore.size(), "max: 1}, exclude: true}");  // the "bore" now holds the whole gear
    std::ofstream(all / "scene.resolved.yaml", std::ios::trunc) << scene;
    const Cli c = peensim({"analyze", all.string()});
    expect_cli(c, 0, {});
    const std::string report = read_file(all / "analysis" / "report.md");
    EXPECT_NE(report.find("**No peened area: coverage is not measured.** All"), std::string::npos) << report.substr(0, 1500);
    EXPECT_NE(report.find("in regions marked `exclude`"), std::string::npos);
    EXPECT_EQ(report.find("gnuplot failed"), std::string::npos) << report;
    EXPECT_EQ(report.find("Coverage now: **"), std::string::npos) << report.substr(0, 1500);
    EXPECT_FALSE(fs::exists(all / "analysis" / "gear_coverage.png"));
}

// ---- run --resume ------------------------------------------------------------------------

// 12. --resume on a finished run said "no checkpoint to resume from".
TEST(HostileInputs3, ResumingAFinishedRunSaysItIsFinishedAndWhere) {
    Runs& r = runs();
    TempDir dir;
    const fs::path done = copy_run(r.rod, dir.path / "done");
    const std::string before = read_file(done / "impacts.csv");
    expect_cli(peensim({"run", kScenes + "rod.yaml", "-o", done.string(), "--set", "process.duration=0.1", "--resume"}), 0,
               {"nothing to resume: the run in " + done.string() + " already finished", "its results are in",
                "impacts.csv, summary.json, analysis/"});
    EXPECT_EQ(read_file(done / "impacts.csv"), before);  // untouched
    expect_cli(peensim({"run", kScenes + "rod.yaml", "-o", done.string(), "--set", "process.duration=0.2", "--resume"}), 2,
               {"summary.json", "finished with another scene (or other --set values, or mesh files whose bytes",
                "(what differs: process: the run had `duration: 0.1  # s`, now `duration: 0.2  # s`)", "run without --resume"});
    expect_cli(peensim({"run", kScenes + "rod.yaml", "-o", (dir.path / "never").string(), "--resume"}), 1,
               {"no checkpoint to resume from"});
}

}  // namespace
}  // namespace peensim::testing
