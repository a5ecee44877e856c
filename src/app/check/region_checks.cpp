#include "app/check/region_checks.h"

#include "analysis/regions.h"
#include "common/input_error.h"
#include "model/shot_cavity.h"

namespace peensim {

std::vector<std::optional<RegionSet>> component_regions(const Model& model) {
    std::vector<std::optional<RegionSet>> out(model.components.size());
    for (std::size_t i = 0; i < model.components.size(); ++i) {
        const ComponentDesc& desc = model.description.components[i];
        if (desc.regions.empty()) continue;
        try {
            out[i].emplace(*model.components[i].mesh, desc.regions);
        } catch (const InputError& e) {  // a group the mesh does not have: said with the component's path
            throw InputError(e.where(), component_field(i) + "." + e.field(), e.problem());
        }
    }
    return out;
}

std::vector<AssemblyIssue> region_issues(const Model& model, const std::vector<std::optional<RegionSet>>& sets) {
    std::vector<AssemblyIssue> out;
    for (std::size_t i = 0; i < sets.size(); ++i) {
        if (!sets[i]) continue;
        const RegionSet& regions = *sets[i];
        const ComponentDesc& desc = model.description.components[i];
        for (std::size_t r = 0; r < regions.size(); ++r) {
            if (regions.area_m2(r) > 0.0) continue;
            out.push_back({false, regions.entry(r).where, component_field(i) + ".regions[" + regions.name(r) + "]",
                           "region '" + regions.name(r) + "' selects none of the surface of '" + desc.name +
                               "'; its conditions are in the component's frame (the mesh's, after mesh_unit): "
                               "see them drawn with `peensim render-regions`",
                           std::nullopt});
        }
    }
    return out;
}

}  // namespace peensim
