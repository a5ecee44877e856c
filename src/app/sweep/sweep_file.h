// A sweep file: a sweep written down (kept beside a study, rerun, reviewed) instead of typed:
//
//   scene: ../scenes/rotating-gear.yaml      # relative to this file
//   seeds: 3                                  # replicates per variant (default 1)
//   set: ["process.duration=2 s"]             # every run, as --set
//   vary:                                     # a grid: every combination
//     components[gear].motion.speed: [15 rpm, 30 rpm, 60 rpm]
//   # or instead of vary, variants one by one, each named:
//   variants:
//     - {name: slow, set: {components[gear].motion.speed: 15 rpm}}
//     - {name: fast-big, set: {components[gear].motion.speed: 60 rpm, shot.diameter: 3 mm}}
//   baseline: slow                            # default: the first variant
#pragma once

#include <string>
#include <vector>

#include "app/sweep/sweep_plan.h"

namespace peensim {

struct SweepFile {
    std::string scene_path;              // resolved against the sweep file's directory
    int seeds = 0;                       // 0: not given
    std::vector<std::string> overrides;  // `set`
    SourceLocation set_origin;           // the `set` key's line
    std::vector<SweepAxis> axes;         // `vary` (each with its line)
    std::vector<SweepVariant> variants;  // `variants` (each with its line)
    std::string baseline;
    SourceLocation baseline_origin;
};

// A YAML file whose top level is a map with a `scene` key, or with the keys of a sweep (vary,
// variants, seeds, set, baseline) and none of a scene's: a sweep file that forgot its scene is
// read as one, and told so, not read as a scene and told that `vary` is an unknown key.
bool is_sweep_file(const std::string& path);

// Throws InputError (file, line, field, what was expected) for a file that is not a sweep.
SweepFile read_sweep_file(const std::string& path);

}  // namespace peensim
