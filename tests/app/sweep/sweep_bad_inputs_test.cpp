// The catalogue of hostile sweep inputs (issue 29): each one run by the real binary is refused with
// exit 2 and a message naming where the mistake is (the option, or the sweep file's line) and what
// was expected, within a few seconds, before any run starts (no run directory is made). A case is
// a command line, the files it reads (a sweep file, a scene) and the phrases its message must hold.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "app/run/run_job.h"
#include "support/child_process.h"
#include "support/files.h"
#include "support/shipped_scenes.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace peensim::testing {
namespace {

const std::string kSource = PEENSIM_SOURCE_DIR;
const std::string kGear = kSource + "/scenes/gear.yaml";

// "1,2,...,n" (from `first`), as `seq -s, first n` writes it.
std::string numbers(int first, int n, const std::string& unit = "") {
    std::string s;
    for (int k = 0; k < n; ++k) s += (k ? "," : "") + std::to_string(first + k) + unit;
    return s;
}

// n levels of lists around 1: "[[[1]]]".
std::string nested_list(int n) {
    return std::string(static_cast<std::size_t>(n), '[') + "1" + std::string(static_cast<std::size_t>(n), ']');
}

// The rod scene with process.seed written as `seed`.
std::string rod_with_seed(const std::string& seed) {
    std::string text = read_file(kRod);
    const std::string line = "  seed: 1\n";
    text.replace(text.find(line), line.size(), "  seed: " + seed + "\n");
    // Its meshes are found from its own directory: the copy points at them.
    for (std::size_t at = 0; (at = text.find("../assets/", at)) != std::string::npos;)
        text.replace(at, 3, kSource + "/"), at += kSource.size();
    return text;
}

struct BadSweep {
    std::string name;
    std::vector<std::string> args;                           // after the binary; "{D}" = the test's directory
    std::vector<std::pair<std::string, std::string>> files;  // written into {D} first: name, text
    std::vector<std::string> phrases;                        // each must be in the message
};

std::vector<BadSweep> catalogue() {
    const std::string study = "{D}/study.yaml";
    return {
        // 1. Bounds, checked before the grid is built.
        {"a --vary of 20 000 values",
         {"sweep", kGear, "-o", "{D}/out", "--vary", "process.seed=" + numbers(1, 20000)},
         {},
         {"--vary: process.seed: 20000 values; expected at most 1000 values per --vary (replicates of one variant: --seeds)"}},
        {"a grid of 5 x 20 values (3.2 M runs)",
         {"sweep", kGear, "-o", "{D}/out", "--vary", "process.seed=" + numbers(1, 20), "--vary", "shot.count=" + numbers(100, 20), "--vary",
          "process.duration=" + numbers(1, 20, " s"), "--vary", "shot.diameter=" + numbers(1, 20, " mm"), "--vary",
          "accuracy.impact_speed=" + numbers(1, 20, " cm/s")},
         {},
         {"--vary: a grid of 20 x 20 x 20 x 20 x 20 values x 1 seed make 3200000 runs; expected at most 10000 runs in a sweep"}},
        {"1000 values x 11 seeds",
         {"sweep", kGear, "-o", "{D}/out", "--vary", "process.seed=" + numbers(1, 1000), "--seeds", "11"},
         {},
         {"--vary: process.seed: 1000 values x 11 seeds make 11000 runs; expected at most 10000 runs"}},
        {"--seeds 0",
         {"sweep", kRod, "-o", "{D}/out", "--seeds", "0"},
         {},
         {"--seeds: expected 1 to 1000 replicates per variant, got '0'"}},
        {"a sweep file's seeds: 0",
         {"sweep", study, "-o", "{D}/out"},
         {{"study.yaml", "scene: " + kRod + "\nseeds: 0\nvary: {shot.count: [64]}\n"}},
         {"study.yaml:2:8: seeds: expected 1 to 1000 replicates per variant, got '0'"}},
        // 2. A value twice, also written differently.
        {"--vary process.seed=1,1",
         {"sweep", kRod, "-o", "{D}/out", "--vary", "process.seed=1,1"},
         {},
         {"--vary: process.seed: the value '1' is given twice; expected each value once"}},
        {"--vary with 1 mm and 0.001 m",
         {"sweep", kRod, "-o", "{D}/out", "--vary", "shot.diameter=1 mm,2 mm,0.001 m"},
         {},
         {"--vary: shot.diameter: '0.001 m' is the value '1 mm' again (0.001); expected each value once"}},
        {"a sweep file's vary with 64 and 6.4e1",
         {"sweep", study, "-o", "{D}/out"},
         {{"study.yaml", "scene: " + kRod + "\nvary:\n  shot.count: [64, 6.4e1]\n"}},
         {"study.yaml:3:3: vary.shot.count: '6.4e1' is the value '64' again (64); expected each value once"}},
        {"two variants setting the same",
         {"sweep", study, "-o", "{D}/out"},
         {{"study.yaml", "scene: " + kRod + "\nvariants:\n  - {name: a, set: {shot.count: 64}}\n  - {name: b, set: {shot.count: '64'}}\n"}},
         {"study.yaml:4:5: variants[1].set: variant 'b' sets the same values as variant 'a'; expected each variant to differ"}},
        // 3. A seed beyond 64 bits, wherever a whole number is given.
        {"a scene file's seed",
         {"check", "{D}/scene.yaml"},
         {{"scene.yaml", rod_with_seed("99999999999999999999999")}},
         {"scene.yaml:11:9: process.seed: expected a whole number >= 0, got '99999999999999999999999' (beyond 64 bits"}},
        {"--set process.seed",
         {"check", kRod, "--set", "process.seed=99999999999999999999999"},
         {},
         {"<--set>: process.seed: expected a whole number >= 0, got '99999999999999999999999' (beyond 64 bits"}},
        {"--set process.seed=1e23 (an exponent)",
         {"check", kRod, "--set", "process.seed=1e23"},
         {},
         {"<--set>: process.seed: expected a whole number >= 0, got '1e23' (beyond 64 bits"}},
        {"--set shot.count=1e30", {"check", kRod, "--set", "shot.count=1e30"}, {}, {"<--set>: shot.count: expected a whole number"}},
        {"--vary process.seed",
         {"sweep", kRod, "-o", "{D}/out", "--vary", "process.seed=5,99999999999999999999999"},
         {},
         {"--vary: process.seed: expected a whole number >= 0, got '99999999999999999999999' (beyond 64 bits",
          "(variant 'seed-99999999999999999999999': process.seed=99999999999999999999999)"}},
        {"a sweep file's set",
         {"sweep", study, "-o", "{D}/out"},
         {{"study.yaml", "scene: " + kRod + "\nset: [process.seed=99999999999999999999999]\nvary: {shot.count: [64]}\n"}},
         {"study.yaml:2:6: set: process.seed: expected a whole number >= 0, got '99999999999999999999999' (beyond 64 bits"}},
        {"a sweep file's vary",
         {"sweep", study, "-o", "{D}/out"},
         {{"study.yaml", "scene: " + kRod + "\nvary:\n  process.seed: [1, 99999999999999999999999]\n"}},
         {"study.yaml:3:3: vary.process.seed: expected a whole number >= 0, got '99999999999999999999999' (beyond 64 bits"}},
        {"seeds past the largest seed",
         {"sweep", kRod, "-o", "{D}/out", "--set", "process.seed=9223372036854775807", "--seeds", "2"},
         {},
         {"process.seed 9223372036854775807 and 2 replicates go past the largest seed, 9223372036854775807"}},
        // 4. A sweep file without its scene.
        {"a sweep file without scene:",
         {"sweep", study, "-o", "{D}/out"},
         {{"study.yaml", "seeds: 2\nvary:\n  shot.count: [64, 128]\n"}},
         {"study.yaml:1:1: scene: missing the scene file: expected `scene:` with its path (relative to this sweep file) in a sweep file"}},
        // 5. Bad variants, blamed on the sweep file's line (or --vary).
        {"a sweep file's variant name",
         {"sweep", study, "-o", "{D}/out"},
         {{"study.yaml",
           "scene: " + kRod + "\nvariants:\n  - {name: ok, set: {shot.count: 64}}\n  - {name: a/b, set: {shot.count: 128}}\n"}},
         {"study.yaml:4:5: variants[1].name: variant name 'a/b': expected letters, digits, '.', '-' or '_'"}},
        {"a sweep file's variant field",
         {"sweep", study, "-o", "{D}/out"},
         {{"study.yaml",
           "scene: " + kRod + "\nvariants:\n  - {name: ok, set: {shot.count: 64}}\n  - {name: bad, set: {shot.colour: red}}\n"}},
         {"study.yaml:4:5: variants[1]: shot.colour: unknown key 'colour' in shot", "(variant 'bad': shot.colour=red)"}},
        {"a sweep file's vary field in a grid",
         {"sweep", study, "-o", "{D}/out"},
         {{"study.yaml", "scene: " + kRod + "\nvary:\n  shot.count: [64, 128]\n  shot.colour: [red]\n"}},
         {"study.yaml:4:3: vary.shot.colour: unknown key 'colour' in shot", "(the value: shot.colour=red)"}},
        {"a --vary field",
         {"sweep", kRod, "-o", "{D}/out", "--vary", "shot.colour=red,blue"},
         {},
         {"--vary: shot.colour: unknown key 'colour' in shot", "(variant 'colour-red': shot.colour=red)"}},
        {"a sweep file's baseline",
         {"sweep", study, "-o", "{D}/out"},
         {{"study.yaml", "scene: " + kRod + "\nvary: {shot.count: [64]}\nbaseline: nothing\n"}},
         {"study.yaml:3:11: baseline: no variant is named 'nothing'"}},
        // 6. Nesting: the one limit (the Python API's too: tests/python/test_hostile_inputs.py).
        {"--set nested 200 deep",
         {"check", kRod, "--set", "process.gravity=" + nested_list(200)},
         {},
         {"<--set>: process.gravity: the value is not valid YAML: maps and lists nested deeper than 64 levels; expected at most 64"}},
        {"a scene file nested 200 000 deep",
         {"check", "{D}/deep.yaml"},
         {{"deep.yaml", "name: " + nested_list(200000) + "\n"}},
         {"deep.yaml:1:", "invalid YAML: maps and lists nested deeper than 64 levels; expected at most 64"}},
    };
}

std::string with_dir(std::string s, const fs::path& dir) {
    for (std::size_t at = 0; (at = s.find("{D}", at)) != std::string::npos;) s.replace(at, 3, dir.string()), at += dir.string().size();
    return s;
}

TEST(SweepBadInputs, EachIsRefusedAtOnceWithExitTwoNamingWhereBeforeAnyRun) {
    constexpr double kAtOnce = 20.0;  // s: each case takes well under 1 s alone; the bound leaves room for a loaded machine
    for (const BadSweep& c : catalogue()) {
        TempDir dir;
        for (const auto& [name, text] : c.files) std::ofstream(dir.path / name, std::ios::binary) << text;
        std::vector<std::string> argv{PEENSIM_BINARY};
        for (const std::string& a : c.args) argv.push_back(with_dir(a, dir.path));
        ChildProcess peensim(argv, (dir.path / "stdout").string(), (dir.path / "stderr").string());
        EXPECT_EQ(peensim.wait_exit(kAtOnce), std::optional<int>(kExitInputError)) << c.name << ": " << read_file(dir.path / "stderr");
        const std::string said = read_file(dir.path / "stderr");
        for (const std::string& phrase : c.phrases)
            EXPECT_NE(said.find(with_dir(phrase, dir.path)), std::string::npos) << c.name << ": " << said;
        EXPECT_FALSE(fs::exists(dir.path / "out")) << c.name << ": a run directory was made";
    }
}

}  // namespace
}  // namespace peensim::testing
