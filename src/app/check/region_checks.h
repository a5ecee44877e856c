// The regions of a scene checked before any run (they used to be built only by the analysis, at
// the end of a run): a `group` the mesh does not have is an error (RegionSet throws it), and a
// region that selects none of its component's surface is a warning (an error with --strict) that
// says where to look. Users wrote `group: nosuchgroup` and a box in the wrong frame and learned of
// it from an empty row of the report.
#pragma once

#include <optional>
#include <vector>

#include "analysis/regions.h"
#include "model/assembly_checks.h"
#include "model/model.h"

namespace peensim {

// Per component, its region set (none for a component without regions). Throws InputError for a
// `group` its mesh does not have, with the component's path.
std::vector<std::optional<RegionSet>> component_regions(const Model& model);

std::vector<AssemblyIssue> region_issues(const Model& model, const std::vector<std::optional<RegionSet>>& regions);

}  // namespace peensim
