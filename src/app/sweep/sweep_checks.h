// A sweep's variants read as their runs will read them, before any run starts: every bad value is
// an input error (exit 2) blamed on where it was given (the sweep file's line, or --vary), not on
// the `--set` the runs are given; a variant that sets process.seed has its replicates start there.
// The checks print their progress when there are many.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "app/sweep/sweep_plan.h"
#include "scene/scene_description.h"

namespace peensim {

// Where a sweep's own overrides (every run's) were given: a sweep file's `set` (its line), then the
// command line's --set (left as the scene parser reports them).
struct SweepOverrides {
    std::vector<std::string> from_file;
    SourceLocation file_origin;
    std::vector<std::string> from_command_line;
};

// The scene as every run of the sweep reads it (without the variants' values). Throws InputError.
SceneDescription read_sweep_scene(const std::string& scene_path, const SweepOverrides& overrides);

// Reads the scene with each value of each axis (a grid of several axes: first each value alone,
// so a bad value is named as such), then with each variant (a listed one: blamed on its line); re-plans the replicates of a variant
// that sets process.seed. A variant's STEP or IGES part that this installation cannot read at all
// is an input error too, blamed where the part was given (the scene's mesh: line, the variant, or
// the sweep's own set: `where_set`, whose texts make plan.overrides). Progress lines on `out`
// after the first second, about one a second.
void check_sweep_variants(const std::string& scene_path, SweepPlan& plan, const SweepOverrides& where_set, std::ostream& out);

// A finished run in the plan's folders that ran another scene than the plan gives it (the scene
// file edited, another --set, a mesh file rewritten in place, or a variant's name now standing for
// other values: two files of one name) is an input error: the sweep would skip it and compare its
// results as the variant's. So is an interrupted run whose checkpoint is of another scene: its
// resume would be refused after other runs had run with the new scene beside it.
// How the refusal names the job and its entries: a sweep's variants, an optimisation's settings.
struct StaleRunWords {
    const char* job = "sweep";
    const char* entry = "variant";
};
void check_finished_runs(const std::string& scene_path, const SweepPlan& plan, const StaleRunWords& words = {});

}  // namespace peensim
