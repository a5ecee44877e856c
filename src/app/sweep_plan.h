// What a sweep runs: the variants of a scene (every combination of the values each --vary gives a
// scene field) times seed replicates, each one an ordinary run directory. Pure: a plan is a
// function of the command line (and the scene's seed), so a sweep resumed, or run by other
// processes, runs the very same runs in the very same directories.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace peensim {

// One --vary: a scene path and its values, as text (`--set` reads each).
struct SweepAxis {
    std::string path;
    std::vector<std::string> values;
};

struct SweepVariant {
    std::string name;                                       // directory name: [A-Za-z0-9._-]
    std::vector<std::pair<std::string, std::string>> set;  // (path, value) per axis
};

struct SweepRun {
    std::size_t variant = 0;           // index into SweepPlan::variants
    int replicate = 0;                 // 0 .. seeds - 1
    std::uint64_t seed = 0;            // process.seed of this run
    std::string dir;                   // its run directory (output_dir/<variant>/s<replicate>)
    std::vector<std::string> overrides;  // every --set of the run: the sweep's, the variant's, the seed
};

struct SweepPlan {
    std::vector<SweepAxis> axes;
    std::vector<SweepVariant> variants;  // the grid, the first axis slowest
    int seeds = 1;
    std::vector<SweepRun> runs;  // variant by variant, replicates in order
};

// The value a variant gives `path` ("" if it leaves the scene's).
std::string sweep_value(const SweepVariant& variant, const std::string& path);

// Reads "path=v1,v2,..." (commas inside [] or {} belong to a value, so vectors and tables vary
// too). Throws std::invalid_argument naming the spec and what was expected.
SweepAxis parse_sweep_axis(const std::string& spec);

// The plan: every combination of the axes' values, `seeds` replicates each with process.seed =
// base_seed + replicate; `overrides` (the sweep's --set) come first in every run.
SweepPlan plan_sweep(const std::vector<SweepAxis>& axes, int seeds, std::uint64_t base_seed, const std::vector<std::string>& overrides,
                     const std::string& output_dir);

// The plan of variants listed one by one (a sweep file's `variants`: each named, each setting
// paths of its own); axes: every path any of them sets, in order of appearance, with the values
// seen. Throws std::invalid_argument for a name twice or outside [A-Za-z0-9._-].
SweepPlan plan_sweep_variants(const std::vector<SweepVariant>& variants, int seeds, std::uint64_t base_seed,
                              const std::vector<std::string>& overrides, const std::string& output_dir);

// A variant's directory name from its values: "<last key>-<value>" per axis joined by "_", every
// character outside [A-Za-z0-9.-] dropped ("components[gear].motion.speed" = "30 rpm" -> "speed-30rpm").
std::string sweep_variant_name(const std::vector<std::pair<std::string, std::string>>& set);

}  // namespace peensim
