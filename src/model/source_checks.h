// Nozzles checked against the assembly before any run: a nozzle whose exit lies inside a solid
// component (a part, a fixture, an Almen holder or the sonotrode) would emit every shot inside it.
// A tester's nozzle placed by a target and a distance that ran back into the part passed `check`,
// then emitted 100 shot into the part (100 deep penetrations, 0 impacts, exit 0).
#pragma once

#include <vector>

#include "model/assembly_checks.h"
#include "model/model.h"

namespace peensim {

std::vector<AssemblyIssue> source_issues(const Model& model);

}  // namespace peensim
