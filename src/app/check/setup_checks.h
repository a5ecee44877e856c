// Every check of a scene's setup that a run and `check` make before any shot flies: plausibility
// (process window, mesh units, plain numbers for lengths), then the shot's cavity (the chamber
// closed around the sonotrode) and the assembly (model/assembly_checks.h). Issues are written to
// `err` as they are found, so the warnings of a scene are seen even when an error follows; an
// error (with `strict`, a warning too) throws InputError (exit 2).
#pragma once

#include <iosfwd>
#include <memory>
#include <optional>
#include <vector>

#include "analysis/regions.h"
#include "common/random.h"
#include "model/assembly_checks.h"
#include "model/model.h"
#include "model/shot_cavity.h"

namespace peensim {

struct SetupCheck {
    Random rng;                          // the placement's generator, after the cavity's probes
    std::unique_ptr<ShotCavity> cavity;  // null without a sonotrode (a scene fed by sources)
    AssemblyReport assembly;
    std::size_t warnings = 0;
    std::vector<std::optional<RegionSet>> regions;  // per component (none without regions): the coverage geometry takes them
};

// found: if given, receives the assembly's issues before any is thrown (the check picture marks them).
SetupCheck check_setup(const Model& model, bool strict, std::ostream& err, std::vector<AssemblyIssue>* found = nullptr);

// Writes the issues (all but the error it throws), then throws InputError for the first error, or
// with `strict` the first warning. Returns the number of warnings.
std::size_t report_setup_issues(const std::vector<AssemblyIssue>& issues, bool strict, std::ostream& err);

}  // namespace peensim
