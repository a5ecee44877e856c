// A mutation fuzz loop over what users hand peensim: scene files, mesh files, sweep files and
// --vary strings (read, planned and every variant checked, as a sweep does before its runs), and
// (issue 29) almen-fit's CSV files, export-fem's arguments, analyze's window (--from, --to), render
// sizes and trade's arguments. Each mutant (bytes flipped, inserted, deleted, lines duplicated or
// dropped, numbers replaced by extreme ones) must be read or refused with an input error (exit 2),
// never anything else: no other exception, no crash (the test binary would die), no hang (CTest's
// timeout). Fixed seeds, so a failure repeats; bounded by a count and a few seconds of wall time
// per input.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

#include "app/almen/almen_fit_job.h"
#include "app/analysis/analyze_job.h"
#include "app/bench/trade_job.h"
#include "app/fem/export_fem_job.h"
#include "app/run/run_job.h"
#include "app/sweep/sweep_checks.h"
#include "app/sweep/sweep_file.h"
#include "app/sweep/sweep_plan.h"
#include "common/input_error.h"
#include "common/units.h"
#include "geometry/mesh_loader.h"
#include "scene/scene_parser.h"
#include "support/files.h"
#include "support/run_in_process.h"
#include "support/shell_command.h"
#include "support/temp_dir.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

// The suite's bounds; PEENSIM_FUZZ_MUTANTS and PEENSIM_FUZZ_SEED (added to every input's seed)
// run a longer or another campaign by hand, and PEENSIM_FUZZ_DUMP=FILE writes each mutant there
// before it is read (the last one is the culprit of a hang or a crash).
constexpr int kMutantsPerInput = 600;
constexpr double kSecondsPerInput = 4.0;
constexpr int kMinMutants = 60;

int mutants_per_input() {
    const char* n = std::getenv("PEENSIM_FUZZ_MUTANTS");
    return n ? std::max(1, std::atoi(n)) : kMutantsPerInput;
}

std::uint64_t seed_offset() {
    const char* n = std::getenv("PEENSIM_FUZZ_SEED");
    return n ? std::strtoull(n, nullptr, 10) : 0;
}

const char* const kExtremes[] = {"0",  "-1", "1e308", "-1e308", "nan",    "inf",     "4294967296", "99999999999999999999", "1e-300", "\"\"",
                                 "[]", "{}", "~",     "2 mm",   "0.0 um", "1e9 rpm", "-0"};

std::string mutate(const std::string& text, std::mt19937_64& rng) {
    std::string s = text;
    std::uniform_int_distribution<int> kind(0, 6);
    const int edits = 1 + static_cast<int>(rng() % 3);
    for (int e = 0; e < edits && !s.empty(); ++e) {
        const std::size_t at = rng() % s.size();
        switch (kind(rng)) {
            case 0: s[at] = static_cast<char>(s[at] ^ (1 << (rng() % 8))); break;  // a flipped bit
            case 1: s.insert(at, 1, static_cast<char>(rng() % 256)); break;        // a stray byte
            case 2: s.erase(at, 1 + rng() % 16); break;                            // bytes lost
            case 3: {                                                              // a line twice
                const std::size_t b = s.rfind('\n', at), end = s.find('\n', at);
                const std::size_t from = b == std::string::npos ? 0 : b + 1;
                s.insert(from, s.substr(from, (end == std::string::npos ? s.size() : end + 1) - from));
                break;
            }
            case 4: s.resize(at); break;  // cut short
            case 5: {                     // an extreme number
                std::size_t d = at;
                while (d < s.size() && !std::isdigit(static_cast<unsigned char>(s[d]))) ++d;
                std::size_t end = d;
                while (end < s.size() && (std::isdigit(static_cast<unsigned char>(s[end])) || s[end] == '.' || s[end] == 'e')) ++end;
                if (d < s.size()) s.replace(d, end - d, kExtremes[rng() % std::size(kExtremes)]);
                break;
            }
            default: s.insert(at, s.substr(rng() % s.size(), 1 + rng() % 64)); break;  // a chunk copied
        }
    }
    return s;
}

// Runs `read` on mutants of `original`: it may succeed or throw InputError, nothing else. Inputs
// whose every read does real work (an export, an analysis) try fewer: `min_mutants` at least.
template <class Read>
void fuzz(const std::string& name, const std::string& original, std::uint64_t seed, Read&& read, int min_mutants = kMinMutants) {
    std::mt19937_64 rng(seed + seed_offset());
    const auto start = std::chrono::steady_clock::now();
    const int mutants = mutants_per_input();
    const double seconds = std::getenv("PEENSIM_FUZZ_MUTANTS") ? 1e9 : kSecondsPerInput;
    int tried = 0, refused = 0;
    for (; tried < mutants; ++tried) {
        // The time bound only shortens a campaign past its first kMinMutants: a slow build (the
        // sanitizers: assimp's OBJ reader takes ~90 ms a mutant there) still tries that many.
        if (tried >= min_mutants && std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds) break;
        const std::string mutant = mutate(original, rng);
        if (std::getenv("PEENSIM_FUZZ_DUMP")) std::ofstream(std::getenv("PEENSIM_FUZZ_DUMP"), std::ios::binary | std::ios::trunc) << mutant;
        try {
            read(mutant);
        } catch (const InputError&) {
            ++refused;
        } catch (const std::exception& e) {
            ADD_FAILURE() << name << ", mutant " << tried << " (seed " << seed << "): not an input error: " << e.what();
        }
    }
    std::cout << "[ fuzz     ] " << name << ": " << tried << " mutants, " << refused << " refused with an input error\n";
    EXPECT_GE(tried, std::min(min_mutants, mutants));
}

TEST(FuzzInputs, SceneFilesAreReadOrRefusedWithAnInputError) {
    const std::string scenes = std::string(PEENSIM_SOURCE_DIR) + "/scenes/";
    std::uint64_t seed = 1;
    // The shipped scenes that hold every section: nozzles, sinks and a shot mix (nozzle-mix), soft
    // settings (gear-soft), regions and rotation (rotating-gear), an Almen strip (almen).
    for (const char* name : {"rod.yaml", "rotating-gear.yaml", "almen.yaml", "nozzle-mix.yaml", "gear-soft.yaml"}) {
        const std::string path = scenes + name;
        fuzz(name, read_file(path), seed++, [&](const std::string& text) { parse_scene_text(text, path); });
    }
}

// What `peensim sweep` does before its first run: the scene with the sweep's own overrides, the plan
// (its bounds, its duplicates), every variant read as its runs will read it.
void check_sweep(const std::string& scene_path, const SweepOverrides& overrides, const std::vector<SweepAxis>& axes,
                 const std::vector<SweepVariant>& listed, int seeds) {
    const SceneDescription scene = read_sweep_scene(scene_path, overrides);
    std::vector<std::string> all = overrides.from_file;
    all.insert(all.end(), overrides.from_command_line.begin(), overrides.from_command_line.end());
    SweepPlan plan = listed.empty() ? plan_sweep(axes, seeds, scene.process.seed, all, "out")
                                    : plan_sweep_variants(listed, seeds, scene.process.seed, all, "out");
    std::ostringstream progress;
    check_sweep_variants(scene_path, plan, {}, progress);
}

TEST(FuzzInputs, SweepFilesAreReadOrRefusedWithAnInputError) {
    TempDir dir;
    const std::string rod = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml";
    const std::vector<std::pair<std::string, std::string>> inputs{
        {"grid.yaml", "scene: " + rod +
                          "\nseeds: 2\nset: [\"process.duration=10 ms\"]\nvary:\n  shot.count: [64, 128]\n"
                          "  process.gravity: [[0, 0, -9.81], [0, -9.81, 0]]\nbaseline: count-64_gravity-00-9.81\n"},
        {"variants.yaml", "scene: " + rod +
                              "\nseeds: 1\nvariants:\n  - {name: few, set: {shot.count: 64, process.seed: 3}}\n"
                              "  - {name: many, set: {shot.count: 128, shot.diameter: 1.5 mm}}\nbaseline: many\n"},
    };
    std::uint64_t seed = 200;
    for (const auto& [name, content] : inputs) {
        const fs::path path = dir.path / name;
        fuzz(name, content, seed++, [&](const std::string& text) {
            std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
            if (!is_sweep_file(path.string())) {  // read as a scene then, as `peensim sweep` does
                (void)parse_scene_file(path.string());
                return;
            }
            const SweepFile f = read_sweep_file(path.string());
            check_sweep(f.scene_path, SweepOverrides{f.overrides, f.set_origin, {}}, f.axes, f.variants, f.seeds > 0 ? f.seeds : 1);
        });
    }
}

TEST(FuzzInputs, VaryStringsAreReadOrRefusedWithAnInputError) {
    const std::string rod = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml";
    std::uint64_t seed = 300;
    for (const char* spec : {"shot.count=64,128,256", "process.gravity=[0, 0, -9.81],[0, -9.81, 0]", "shot.diameter=1 mm,1.5 mm,0.002 m",
                             "components[rod].material=copper,steel", "process.seed=1,2,3"}) {
        fuzz(std::string("--vary ") + spec, spec, seed++, [&](const std::string& mutant) {
            check_sweep(rod, SweepOverrides{{}, {}, {"process.duration=10 ms"}},
                        {parse_sweep_axis(mutant), parse_sweep_axis("accuracy.travel_fraction=0.25,0.2")}, {}, 1);
        });
    }
}

TEST(FuzzInputs, MeshFilesAreReadOrRefusedWithAnInputError) {
    TempDir dir;
    const std::string bad = std::string(PEENSIM_SOURCE_DIR) + "/tests/meshes_bad/";
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 4\n"
        "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    const std::vector<std::pair<std::string, std::string>> inputs{
        {"tetrahedron.stl", read_file(std::string(PEENSIM_SOURCE_DIR) + "/tests/scenes_bad/tetrahedron.stl")},
        {"rod-sonotrode.stl", read_file(std::string(PEENSIM_SOURCE_DIR) + "/assets/rod-sonotrode.stl")},
        {"tetrahedron.ply", ply},
        {"tetrahedron.obj", obj},
    };
    std::uint64_t seed = 100;
    for (const auto& [name, content] : inputs) {
        const fs::path path = dir.path / name;
        fuzz(name, content, seed++, [&](const std::string& bytes) {
            std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
            load_mesh(path.string(), 1e-3);
        });
    }
}

// ---- Commands' inputs (issue 29): each mutant goes through the command's job, whose exit code
// must be 0 or 2 (2 is counted as a refusal); 1 (a runtime error) or anything thrown fails.

// A job's exit code as the fuzz loop wants it: 0 passes, 2 is an InputError, anything else fails
// (`err`: what the job printed; read after the job ran).
void expect_read_or_refused(int code, const std::string& err) {
    if (code == kExitInputError) throw InputError({}, "", err);
    if (code != kExitOk) throw std::runtime_error("exit " + std::to_string(code) + ": " + err);
}

// The lines "key<TAB>value" of a mutated option list (lines without a tab are dropped, as the
// command line would not have them).
std::vector<std::pair<std::string, std::string>> options_of(const std::string& text) {
    std::vector<std::pair<std::string, std::string>> o;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        const auto tab = line.find('\t');
        if (tab != std::string::npos) o.emplace_back(line.substr(0, tab), line.substr(tab + 1));
    }
    return o;
}

// A number option as CLI11 reads it (text that is not one is refused, exit 2).
template <class T>
T cli_number(const std::string& option, const std::string& text) {
    std::istringstream in(text);
    T v{};
    in >> v;
    if (in.fail() || !in.eof()) throw InputError({option}, "", "not a number: '" + text + "'");
    return v;
}

TEST(FuzzInputs, AlmenFitCurvesAreFittedOrRefusedWithAnInputError) {
    TempDir dir;
    const std::vector<std::pair<std::string, std::string>> inputs{
        {"usp-example.csv", read_file(std::string(PEENSIM_SOURCE_DIR) + "/scenes/almen-curves/usp-example.csv")},
        {"j2597-set1.csv", read_file(std::string(PEENSIM_SOURCE_DIR) + "/scenes/almen-curves/j2597-set1.csv")},
    };
    std::uint64_t seed = 200;
    for (const auto& [name, content] : inputs) {
        const fs::path path = dir.path / name;
        fuzz(name, content, seed++, [&](const std::string& bytes) {
            std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
            AlmenFitOptions o;
            o.curve_path = path.string();
            o.json_path = (dir.path / "fit.json").string();
            std::ostringstream out, err;
            const int code = almen_fit_job(o, out, err);
            expect_read_or_refused(code, err.str());
        });
    }
}

TEST(FuzzInputs, ExportFemArgumentsAreExportedOrRefusedWithAnInputError) {
    TempDir dir;
    const std::string original =
        "single\t0,0,0,0,0,-50 m/s\nshot-diameter\t0.58 mm\ncenter\t0,0,0\nradius\t1 mm\ngroup-window\t1 ms\nelement-size\t0.05 mm\n"
        "name\tpatch\nimpacts\t1\nyield-stress\t500 MPa\nhardening\t0 MPa\nelements-per-dent\t6\ncontact-times\t2.5\n"
        "shot-divisions\t4\nquarter\t1\nelement\tC3D8I\ndynamics\texplicit\n";
    fuzz(
        "export-fem arguments", original, 300,
        [&](const std::string& text) {
            ExportFemOptions o;
            o.output_dir = (dir.path / "deck").string();
            for (const auto& [key, value] : options_of(text)) {
                if (key == "single") o.single = value;
                if (key == "shot-diameter") o.shot_diameter = value;
                if (key == "center") o.center = value;
                if (key == "radius") o.radius = value;
                if (key == "group-window") o.group_window = value;
                if (key == "element-size") o.element_size = value;
                if (key == "name") o.name = value;
                if (key == "impacts") o.max_impacts = cli_number<int>("--impacts", value);
                if (key == "yield-stress") o.yield_stress = value;
                if (key == "hardening") o.hardening = value;
                if (key == "elements-per-dent") o.elements_per_dent = cli_number<double>("--elements-per-dent", value);
                if (key == "contact-times") o.contact_times = cli_number<double>("--contact-times", value);
                if (key == "shot-divisions") o.shot_divisions = cli_number<int>("--shot-divisions", value);
                if (key == "quarter") o.quarter = value == "1";
                if (key == "element") o.element = value;
                if (key == "dynamics") o.dynamics = value;
            }
            std::ostringstream out, err;
            const int code = export_fem_job(o, out, err);
            expect_read_or_refused(code, err.str());
            // Whatever the name, nothing is written outside the output directory.
            for (const auto& e : fs::directory_iterator(dir.path))
                if (e.path().filename() != "deck") ADD_FAILURE() << "written outside -o: " << e.path();
        },
        20);
}

TEST(FuzzInputs, AnalyzeWindowsAreAnalysedOrRefusedWithAnInputError) {
    TempDir dir;
    InProcessRun r;
    r.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml";
    r.output_dir = (dir.path / "run").string();
    r.overrides = {"process.duration=0.05"};
    ASSERT_EQ(run_in_process(r).code, kExitOk);
    const auto quantity = [](const char* option, const std::string& text, Dimension dim) {
        try {
            return parse_quantity(text, dim);
        } catch (const QuantityError& e) {
            throw InputError({option}, "", e.what());  // as the command line does
        }
    };
    fuzz(
        "analyze --from --to", "from\t0.01 s\nto\t40 ms\nmin-speed\t0.1 m/s\ntarget\t98 %\n", 400,
        [&](const std::string& text) {
            AnalyzeOptions o;
            for (const auto& [key, value] : options_of(text)) {
                if (key == "from") o.from_s = quantity("--from", value, Dimension::time);
                if (key == "to") o.to_s = quantity("--to", value, Dimension::time);
                if (key == "min-speed") o.min_speed_m_per_s = quantity("--min-speed", value, Dimension::speed);
                if (key == "target") o.target_coverage = quantity("--target", value, Dimension::dimensionless);
            }
            std::ostringstream out, err;
            const int code = analyze_job(r.output_dir, out, err, o);
            expect_read_or_refused(code, err.str());
        },
        12);
}

// Through the binary: the sizes are CLI11's to check (a range), and a valid size is drawn.
TEST(FuzzInputs, RenderSizesAreDrawnOrRefusedWithExitTwo) {
    TempDir dir;
    const std::string scene = std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml";
    fuzz(
        "render-regions --width --height", "64\n64\n", 500,
        [&](const std::string& text) {
            std::string clean = text;
            clean.erase(std::remove(clean.begin(), clean.end(), '\0'), clean.end());  // argv cannot hold one
            const auto nl = clean.find('\n');
            const std::string width = clean.substr(0, nl),
                              height = nl == std::string::npos ? "" : clean.substr(nl + 1, clean.find('\n', nl + 1) - nl - 1);
            const auto word = [](const std::string& s) {
                std::string q = "'";
                for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
                return q + "'";
            };
            const ShellResult res = run_shell(std::string(PEENSIM_BINARY) + " render-regions " + word(scene) + " -o " +
                                              word((dir.path / "maps").string()) + " --width " + word(width) + " --height " + word(height));
            const int code = WIFEXITED(res.status) ? WEXITSTATUS(res.status) : -1;
            expect_read_or_refused(code, res.output);
        },
        12);
}

TEST(FuzzInputs, TradeArgumentsAreRunOrRefusedWithAnInputError) {
    TempDir dir;
    TestSceneSpec spec = small_rod_scene("soft", 0.002);
    spec.soft = SoftSpec{};
    spec.shot_count = 4;
    spec.log = {"part"};
    const TestScene scene(spec);
    fuzz(
        "trade arguments",
        "settle\t0.2 ms\nreference-steps\t20\ncsv\t" + (dir.path / "t.csv").string() + "\nplot\t" + (dir.path / "t.png").string() + "\n",
        600,
        [&](const std::string& text) {
            TradeOptions o;
            o.scene_path = scene.scene_path();
            for (const auto& [key, value] : options_of(text)) {
                if (key == "settle") o.settle = value;
                if (key == "reference-steps") o.reference_steps = cli_number<double>("--reference-steps", value);
                if (key == "csv") o.csv_path = value;
                if (key == "plot") o.plot_path = value;
            }
            std::ostringstream out, err;
            const int code = trade_job(o, out, err);
            expect_read_or_refused(code, err.str());
        },
        12);
}

}  // namespace
}  // namespace peensim::testing
