// The regions `peensim new` writes into a scene: for a turning part its two ends (the faces across
// the axis) and 8 sectors of 45 deg about the axis, for a still part its faces by the six ways they
// look. Only those holding some of the part's surface: a region of none would be a warning in
// `check` and an empty row in every report (an L-bracket turning about y leaves sectors empty).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "geometry/axis_frame.h"
#include "geometry/part_envelope.h"
#include "geometry/triangle_mesh.h"
#include "scene/scene_description.h"

namespace peensim {

struct ProposedRegions {
    // As the scene writes them: `facing` entries; the sectors as one `sectors` entry when all 8 hold
    // surface, else a `sector` entry for each that does (named as the `sectors` entry names them).
    std::vector<RegionDesc> entries;
    std::vector<std::string> left_out;  // the candidates holding none of the surface, by name
};

inline constexpr int kProposedSectors = 8;

// mesh and envelope in the part's own frame (m); the turning axis through the envelope's centre.
ProposedRegions propose_regions(const TriangleMesh& mesh, const PartEnvelope& envelope, const std::optional<Axis>& turning_axis);

}  // namespace peensim
