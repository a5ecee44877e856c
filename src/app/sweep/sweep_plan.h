// What a sweep runs: the variants of a scene (every combination of the values each --vary gives a
// scene field) times seed replicates, each one an ordinary run directory. Pure: a plan is a
// function of the command line (and the scene's seed), so a sweep resumed, or run by other
// processes, runs the very same runs in the very same directories.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/input_error.h"

namespace peensim {

// A sweep's bounds, checked before anything is planned, read or run (each run is a whole
// simulation: a larger sweep is a mistake, or a study to split). Replicates come from --seeds.
inline constexpr std::size_t kMaxSweepValues = 1000;  // values of one --vary (or one `vary` key of a sweep file)
inline constexpr std::size_t kMaxSweepRuns = 10000;   // runs of a sweep: variants x seeds
inline constexpr int kMaxSweepSeeds = 1000;           // --seeds: replicates per variant

// "expected 1 to 1000 replicates per variant, got '0'": the one rule and message of the seeds, from
// --seeds, a sweep file's `seeds` or Python's sweep(seeds=...).
std::string sweep_seeds_problem(const std::string& given);

// One --vary: a scene path and its values, as text (`--set` reads each); `origin` and `field` say
// where it was given, for messages: {"--vary"} and the path, or the sweep file's line and "vary.<path>".
struct SweepAxis {
    std::string path;
    std::vector<std::string> values;
    SourceLocation origin{"--vary", 0, 0};
    std::string field;  // "" = the path
};

// Where one setting of a variant was given, when that is not the variant's own place: an
// optimisation's check sets every variable, each written on its own line of the study.
struct SweepSettingOrigin {
    SourceLocation where;
    std::string field;  // "variables.speed.start"
    std::string label;  // "variable 'speed' at its start": how an error names it
};

struct SweepVariant {
    std::string name;                                      // directory name: [A-Za-z0-9._-]
    std::vector<std::pair<std::string, std::string>> set;  // (path, value) per axis
    SourceLocation origin{"--vary", 0, 0};                 // a sweep file's variant: its line
    std::string field;                                     // "variants[2]" for a sweep file's variant
    std::vector<SweepSettingOrigin> set_origins;           // per entry of `set`, or empty: all given at `origin`
};

struct SweepRun {
    std::size_t variant = 0;             // index into SweepPlan::variants
    int replicate = 0;                   // 0 .. seeds - 1
    std::uint64_t seed = 0;              // process.seed of this run
    std::string dir;                     // its run directory (output_dir/<variant>/s<replicate>)
    std::vector<std::string> overrides;  // every --set of the run: the sweep's, the variant's, the seed
};

struct SweepPlan {
    std::vector<SweepAxis> axes;
    std::vector<SweepVariant> variants;  // the grid, the first axis slowest
    bool grid = true;                    // false: variants listed one by one (axes then only name what they set)
    int seeds = 1;
    std::vector<SweepRun> runs;          // variant by variant, replicates in order
    std::vector<std::string> overrides;  // the sweep's own --set, first in every run
    std::string output_dir;
};

// The value a variant gives `path` ("" if it leaves the scene's).
std::string sweep_value(const SweepVariant& variant, const std::string& path);

// Reads "path=v1,v2,..." (commas inside [] or {} belong to a value, so vectors and tables vary
// too). Throws InputError ("--vary") naming the path and what was expected: a malformed spec, more
// than kMaxSweepValues values.
SweepAxis parse_sweep_axis(const std::string& spec);

// The plan: every combination of the axes' values, `seeds` replicates each with process.seed =
// base_seed + replicate; `overrides` (the sweep's --set) come first in every run. Throws
// InputError (at the axis' origin) for a path varied twice, a value given twice (also written
// differently: "1 mm" and "0.001 m"), more values or runs than the bounds above (checked before
// the grid is built), seeds outside 1..kMaxSweepSeeds or past the largest seed.
SweepPlan plan_sweep(const std::vector<SweepAxis>& axes, int seeds, std::uint64_t base_seed, const std::vector<std::string>& overrides,
                     const std::string& output_dir);

// The plan of variants listed one by one (a sweep file's `variants`: each named, each setting
// paths of its own); axes: every path any of them sets, in order of appearance, with the values
// seen. Throws InputError (at the variant's origin) for a name twice or outside [A-Za-z0-9._-], two
// variants setting the same values, and the bounds as plan_sweep's.
SweepPlan plan_sweep_variants(const std::vector<SweepVariant>& variants, int seeds, std::uint64_t base_seed,
                              const std::vector<std::string>& overrides, const std::string& output_dir);

// Listed variants each with its own number of replicates (an optimisation's settings: more seeds
// where an interval needs them), checked as plan_sweep_variants; variant v runs replicates[v]
// seeds from base_seed (1 where none is given). plan.seeds: the most any variant has.
SweepPlan plan_sweep_replicates(const std::vector<SweepVariant>& variants, const std::vector<int>& replicates, std::uint64_t base_seed,
                                const std::vector<std::string>& overrides, const std::string& output_dir);

// A variant that sets process.seed itself: its replicates start there (seed, seed + 1, ...)
// instead of at the scene's. Throws InputError ("--seeds") past the largest seed.
void reseed_variant(SweepPlan& plan, std::size_t variant, std::uint64_t seed);

// A variant's directory name from its values: "<last key>-<value>" per axis joined by "_", every
// character outside [A-Za-z0-9.-] dropped ("components[gear].motion.speed" = "30 rpm" -> "speed-30rpm").
std::string sweep_variant_name(const std::vector<std::pair<std::string, std::string>>& set);

}  // namespace peensim
