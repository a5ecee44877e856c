// A mutation fuzz loop over what users hand peensim: scene files, mesh files, sweep files and
// --vary strings (read, planned and every variant checked, as a sweep does before its runs). Each mutant (bytes
// flipped, inserted, deleted, lines duplicated or dropped, numbers replaced by extreme ones) must
// be read or refused with an input error (exit 2), never anything else: no other exception, no
// crash (the test binary would die), no hang (CTest's timeout). Fixed seeds, so a failure repeats;
// bounded by a count and a few seconds of wall time per input.
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

#include "app/sweep_checks.h"
#include "app/sweep_file.h"
#include "app/sweep_plan.h"
#include "common/input_error.h"
#include "geometry/mesh_loader.h"
#include "scene/scene_parser.h"
#include "support/files.h"
#include "support/temp_dir.h"

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

// Runs `read` on mutants of `original`: it may succeed or throw InputError, nothing else.
template <class Read>
void fuzz(const std::string& name, const std::string& original, std::uint64_t seed, Read&& read) {
    std::mt19937_64 rng(seed + seed_offset());
    const auto start = std::chrono::steady_clock::now();
    const int mutants = mutants_per_input();
    const double seconds = std::getenv("PEENSIM_FUZZ_MUTANTS") ? 1e9 : kSecondsPerInput;
    int tried = 0, refused = 0;
    for (; tried < mutants; ++tried) {
        // The time bound only shortens a campaign past its first kMinMutants: a slow build (the
        // sanitizers: assimp's OBJ reader takes ~90 ms a mutant there) still tries that many.
        if (tried >= kMinMutants && std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds) break;
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
    EXPECT_GE(tried, std::min(kMinMutants, mutants));
}

TEST(FuzzInputs, SceneFilesAreReadOrRefusedWithAnInputError) {
    const std::string scenes = std::string(PEENSIM_SOURCE_DIR) + "/scenes/";
    std::uint64_t seed = 1;
    for (const char* name : {"rod.yaml", "rotating-gear.yaml", "almen.yaml"}) {
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
    check_sweep_variants(scene_path, plan, progress);
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

}  // namespace
}  // namespace peensim::testing
