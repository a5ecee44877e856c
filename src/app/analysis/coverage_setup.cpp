#include "app/analysis/coverage_setup.h"

#include "analysis/part_coverage.h"
#include "analysis/sample_classes.h"
#include "model/facet_reach.h"
#include "scene/shot_mix.h"

namespace peensim {

double part_yield_stress(const SceneDescription& scene, std::size_t ci) {
    for (const MaterialDesc& m : scene.materials)
        if (m.name == scene.components[ci].material) return m.yield_stress_pa.value_or(0.0);
    return 0.0;
}

std::unique_ptr<CoverageProgress> part_coverage(const Model& model, std::size_t ci, ShotCavity* cavity, const SceneDescription& scene,
                                                const RegionSet& regions, double target) {
    const double yield = part_yield_stress(scene, ci);
    if (!(yield > 0.0)) return nullptr;
    const TriangleMesh& mesh = *model.components[ci].mesh;
    std::unique_ptr<CoverageMap> map =
        part_coverage_map(mesh, smallest_diameter_m(scene.shot), largest_diameter_m(scene.shot), scene.shot.density_kg_per_m3, yield);
    const double R = model.min_shot_radius_m;  // the smallest shot of a mix reaches furthest
    SampleClasses classes(*map, mesh, regions, reach_test(model, ci, cavity), R, R / kReachProbesPerRadius);
    return std::make_unique<CoverageProgress>(std::move(map), std::move(classes), target);
}

}  // namespace peensim
