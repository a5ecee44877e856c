// The report's findings a chamber designer acts on beyond the time: the area no shot reaches (how
// much, where, what shot would reach it) and what to change, each change backed by a figure this
// run measured and the command that tests it.
#pragma once

#include <string>
#include <vector>

#include "app/analysis/analysis_report.h"
#include "app/component_analysis.h"
#include "scene/scene_description.h"

namespace peensim {

// "### <part>: out of the shot's reach": its area per region, the shot that would reach it, the
// picture; "" when the shot reaches every counted sample.
std::string unreachable_section(const ComponentAnalysis& part, const ReportContext& context);

// "## What to change": the report's last section.
std::string changes_section(const SceneDescription& scene, const std::vector<ComponentAnalysis>& parts, const ReportContext& context);

// The axis a static part would turn about: through its area centroid along its axis of symmetry
// (the principal axis of its surface whose moment differs most from the other two), world frame.
struct TurningAxis {
    Vec3 point_m = Vec3::Zero();
    Vec3 direction = Vec3::UnitZ();
};
TurningAxis turning_axis(const TriangleMesh& mesh, const ComponentDesc& placement);

}  // namespace peensim
