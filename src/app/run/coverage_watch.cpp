#include "app/run/coverage_watch.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/impact_stream.h"
#include "app/analysis/coverage_geometry.h"
#include "common/float_limits.h"
#include "common/input_error.h"
#include "contact/dent.h"

namespace peensim {

struct CoverageWatch::Part {
    std::string name;
    std::size_t component = 0;
    RegionSet regions;
    std::unique_ptr<CoverageProgress> coverage;
    double yield_stress_pa = 0.0;  // Pa
    // Watched areas: -1 the whole peened area, r region r.
    std::vector<int> watched;

    double reached_at(int area) const {
        return area < 0 ? coverage->reached_at_s() : coverage->region_reached_at_s(static_cast<std::size_t>(area));
    }
};

CoverageWatch::CoverageWatch(CoverageGeometry& geometry, const std::string& resume_log) : model_(*geometry.model()) {
    const Model& model = model_;
    const SceneDescription& scene = model.description;
    target_ = scene.process.until_coverage.value_or(0.98);
    part_of_component_.assign(model.components.size(), -1);
    const std::vector<std::string>& of = scene.process.until_coverage_of;
    for (std::size_t ci = 0; ci < model.components.size(); ++ci) {
        const Component& c = model.components[ci];
        if (!c.logged || !(part_yield_stress(scene, ci) > 0.0)) continue;
        auto part = std::make_unique<Part>();
        part->name = c.name;
        part->component = ci;
        const PartCoverageGeometry* shared = geometry.part(ci);
        part->regions = shared != nullptr ? shared->regions : RegionSet(*c.mesh, scene.components[ci].regions);
        // Every counted region (or the peened area without regions), unless names are given.
        if (of.empty()) {
            for (std::size_t r = 0; r < part->regions.size(); ++r)
                if (!part->regions.excluded(r)) part->watched.push_back(static_cast<int>(r));
            if (part->watched.empty()) part->watched.push_back(-1);
        } else {
            for (const std::string& name : of) {
                if (name == c.name) part->watched.push_back(-1);
                if (name.rfind(c.name + "/", 0) != 0) continue;
                for (std::size_t r = 0; r < part->regions.size(); ++r)
                    if (part->regions.name(r) == name.substr(c.name.size() + 1)) part->watched.push_back(static_cast<int>(r));
            }
            if (part->watched.empty()) continue;
        }
        part->coverage = part_coverage(geometry, ci, target_);  // as the analysis counts it
        part->yield_stress_pa = part_yield_stress(scene, ci);
        // A region without peened area (excluded, or out of reach) can never be reached: not waited
        // for (one named in until_coverage_of is said so).
        std::erase_if(part->watched, [&](int a) {
            if (a < 0 || part->coverage->classes().region_peened_area_m2(static_cast<std::size_t>(a)) > 0.0) return false;
            if (!of.empty()) out_of_reach_.push_back(c.name + "/" + part->regions.name(static_cast<std::size_t>(a)));
            return true;
        });
        part_of_component_[ci] = static_cast<int>(parts_.size());
        parts_.push_back(std::move(part));
    }
    if (std::none_of(parts_.begin(), parts_.end(), [](const auto& p) { return !p->watched.empty(); })) {
        if (!out_of_reach_.empty()) {
            std::string names;
            for (const std::string& n : out_of_reach_) names += (names.empty() ? "'" : ", '") + n + "'";
            throw InputError(
                model.description.process.where, "process.until_coverage_of",
                names + (out_of_reach_.size() == 1 ? " has" : " have") +
                    " no surface a shot can reach (the reach test of every coverage sample), so it can never reach the "
                    "target; expected an area the shot can reach (peensim render-regions draws what they cannot in dark grey)");
        }
        throw InputError(model.description.process.where, "until_coverage",
                         "no watched area has peened area (every region is excluded or out of the shot's reach): nothing can reach the "
                         "target");
    }
    if (!resume_log.empty()) {
        // The dents up to the checkpoint, from the log the resumed run goes on writing.
        std::vector<std::string> names;
        for (const Component& c : model.components) names.push_back(c.name);
        ImpactStream stream(resume_log, names);
        for (auto block = stream.next_block(); !block.empty(); block = stream.next_block())
            for (const IndexedImpact& i : block)
                if (i.component >= 0)
                    add_dent(static_cast<std::size_t>(i.component), i.row.point_m, i.row.vn_in_m_per_s, i.row.shot_diameter_m,
                             i.row.time_s);
    }
}

CoverageWatch::~CoverageWatch() = default;

void CoverageWatch::add_dent(std::size_t component, const Vec3& point_m, double vn, double shot_diameter_m, double time_s) {
    const int p = part_of_component_[component];
    if (p < 0) return;
    Part& part = *parts_[static_cast<std::size_t>(p)];
    const ShotDesc& shot = model_.description.shot;
    const double D = shot_diameter_m > 0.0 ? shot_diameter_m : shot.sizes.front().diameter_m;
    part.coverage->add_dent(point_m, dent_diameter(D, shot.density_kg_per_m3, vn, part.yield_stress_pa), time_s);
}

void CoverageWatch::add(std::span<const ImpactRecord> impacts) {
    for (const ImpactRecord& r : impacts)
        add_dent(static_cast<std::size_t>(r.component), r.point_m, r.vn_in_m_per_s, r.shot_diameter_m, r.time_s);
}

bool CoverageWatch::done() const {
    for (const auto& part : parts_)
        for (int a : part->watched)
            if (std::isnan(part->reached_at(a))) return false;
    return !parts_.empty();
}

std::vector<WatchedArea> CoverageWatch::areas() const {
    std::vector<WatchedArea> out;
    for (const auto& part : parts_)
        for (int a : part->watched) {
            WatchedArea w;
            w.name = a < 0 ? part->name : part->name + "/" + part->regions.name(static_cast<std::size_t>(a));
            w.reached_at_s = part->reached_at(a);
            w.coverage = a < 0 ? part->coverage->coverage() : part->coverage->region_coverage(static_cast<std::size_t>(a));
            out.push_back(std::move(w));
        }
    return out;
}

}  // namespace peensim
