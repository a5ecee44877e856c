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
        std::vector<std::size_t> empty;
        for (std::size_t r = 0; r < regions.size(); ++r)
            if (!(regions.area_m2(r) > 0.0)) empty.push_back(r);
        if (empty.empty()) continue;
        const auto drawn = [](const char* whose) {
            return std::string("; ") + whose +
                   " conditions are in the component's frame (the mesh's, after mesh_unit): see them drawn with `peensim render-regions`";
        };
        if (empty.size() == 1) {
            const std::size_t r = empty.front();
            out.push_back({false, regions.entry(r).where, component_field(i) + ".regions[" + regions.name(r) + "]",
                           "region '" + regions.name(r) + "' selects none of the surface of '" + desc.name + "'" + drawn("its"),
                           std::nullopt});
            continue;
        }
        // Several: one warning naming them (a wrong mesh_unit empties every region that a box or a
        // radius bounds: twenty teeth gave twenty warnings of the same words).
        constexpr std::size_t kNamed = 6;
        std::string names;
        for (std::size_t k = 0; k < std::min(empty.size(), kNamed); ++k) names += (k ? ", '" : "'") + regions.name(empty[k]) + "'";
        if (empty.size() > kNamed) names += " and " + std::to_string(empty.size() - kNamed) + " more";
        const std::string which =
            empty.size() == regions.size()
                ? "none of its " + std::to_string(regions.size()) + " regions (" + names + ") selects any"
                : std::to_string(empty.size()) + " of its " + std::to_string(regions.size()) + " regions (" + names + ") select none";
        out.push_back({false, regions.entry(empty.front()).where, component_field(i) + ".regions",
                       which + " of the surface of '" + desc.name + "'" + drawn("their") +
                           (empty.size() == regions.size() ? ". Is its mesh_unit right?" : ""),
                       std::nullopt});
    }
    return out;
}

}  // namespace peensim
