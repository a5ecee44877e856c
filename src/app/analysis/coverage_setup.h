// The coverage of a logged part as `peensim analyze` and `peensim run --until-coverage` both count
// it: its coverage map (analysis/part_coverage.h) with every sample's reach in the assembly at
// t = 0 (model/facet_reach.h) and its regions (analysis/sample_classes.h), watching a target.
#pragma once

#include <memory>

#include "analysis/coverage_progress.h"
#include "analysis/regions.h"
#include "model/model.h"
#include "model/shot_cavity.h"
#include "scene/scene_description.h"

namespace peensim {

// The yield stress (Pa) of component ci's material, or 0 (no coverage: no dents).
double part_yield_stress(const SceneDescription& scene, std::size_t ci);

// Component ci's coverage (null when its material has no yield stress): regions of its mesh,
// cavity the shot's (nullptr: clearance alone), target (0..1].
std::unique_ptr<CoverageProgress> part_coverage(const Model& model, std::size_t ci, ShotCavity* cavity, const SceneDescription& scene,
                                                const RegionSet& regions, double target);

}  // namespace peensim
