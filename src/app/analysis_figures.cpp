#include "app/analysis_figures.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "analysis/region_stats.h"
#include "app/coverage_verdict.h"
#include "app/almen_analysis.h"

namespace peensim {

namespace {

// JSON has no NaN: a figure that does not exist is null.
nlohmann::ordered_json number(double x) { return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr); }

// The Avrami rate and time to 98 % with their 95 % intervals (coverage_outlook.h).
void put_outlook(nlohmann::ordered_json& o, const CoverageOutlook& x) {
    o["avrami_k_per_s"] = number(x.fitted ? x.k_per_s : NAN);
    o["avrami_k_se_per_s"] = number(x.fitted ? x.k_relative_se * x.k_per_s : NAN);
    o["avrami_k_low_per_s"] = number(x.fitted ? x.k_low_per_s : NAN);
    o["avrami_k_high_per_s"] = number(x.fitted ? x.k_high_per_s : NAN);
    o["time_to_98_s"] = number(x.fitted ? x.time_to_98_s : NAN);
    o["time_to_98_low_s"] = number(x.fitted ? x.time_to_98_low_s : NAN);
    o["time_to_98_high_s"] = number(x.fitted ? x.time_to_98_high_s : NAN);  // null: unbounded
    o["time_to_98_extrapolated"] = x.fitted && x.run_multiple > 1.0;
    o["run_multiple"] = number(x.fitted ? x.run_multiple : NAN);
}

}  // namespace

std::string analysis_figures_json(const std::vector<ComponentAnalysis>& parts, const AnalysisWindow& window) {
    const double duration_s = window.length_s();
    nlohmann::ordered_json j;
    j["duration_s"] = duration_s;
    j["window"] = {{"from_s", window.from_s}, {"to_s", window.to_s}, {"min_speed_mps", window.min_speed_m_per_s}};
    j["target_coverage"] = window.target_coverage;
    j["batches"] = kFigureBatches;
    auto components = nlohmann::ordered_json::array();
    for (const ComponentAnalysis& c : parts) {
        nlohmann::ordered_json o;
        const double n = static_cast<double>(c.impacts);
        o["component"] = c.name;
        o["impacts"] = c.impacts;
        o["impact_rate_per_s"] = number(duration_s > 0.0 ? n / duration_s : NAN);
        o["mean_vn_mps"] = number(c.impacts ? c.speed_sum / n : NAN);
        o["mean_dent_m"] = number(c.impacts && c.coverage ? c.dent_sum / n : NAN);
        o["coverage"] = number(c.coverage ? c.outlook.coverage : NAN);  // of the peened area
        if (c.coverage) {
            const PeenedAreas areas = peened_areas(c);
            o["area_m2"] = areas.total_m2;
            o["peened_area_m2"] = areas.peened_m2;
            o["unreachable_area_m2"] = areas.unreachable_m2;
            o["excluded_area_m2"] = areas.excluded_m2;
            o["share_below_target"] = number(share_below(c, window.target_coverage));
            put_outlook(o, c.outlook);
        }
        if (c.almen) add_almen_figures(o, *c.almen);
        // Batch means: each tenth of the window's impact rate and mean normal speed.
        auto rate = nlohmann::ordered_json::array(), speed = nlohmann::ordered_json::array();
        for (int b = 0; b < kFigureBatches; ++b) {
            const auto k = static_cast<std::size_t>(b);
            const double impacts = static_cast<double>(c.batch_impacts[k]);
            rate.push_back(number(duration_s > 0.0 ? impacts / (duration_s / kFigureBatches) : NAN));
            speed.push_back(number(impacts > 0.0 ? c.batch_speed_sum[k] / impacts : NAN));
        }
        o["batch_impact_rate_per_s"] = std::move(rate);
        o["batch_mean_vn_mps"] = std::move(speed);
        auto regions = nlohmann::ordered_json::array();
        for (std::size_t r = 0; r < c.regions.size(); ++r) {
            const RegionStats x = region_stats(c.regions, r, c.region_tallies[r], c.coverage.get(), c.peened, duration_s);
            nlohmann::ordered_json g{{"region", c.regions.name(r)},
                                     {"excluded", c.regions.excluded(r)},
                                     {"area_m2", x.area_m2},
                                     {"peened_area_m2", x.peened_area_m2},
                                     {"impacts", x.impacts},
                                     {"impact_rate_per_s", number(duration_s > 0.0 ? static_cast<double>(x.impacts) / duration_s : NAN)},
                                     {"mean_vn_mps", number(x.mean_normal_speed)},
                                     {"coverage", number(x.coverage)}};
            if (!c.region_outlooks.empty()) put_outlook(g, c.region_outlooks[r]);
            regions.push_back(std::move(g));
        }
        o["regions"] = std::move(regions);
        if (c.coverage && !c.regions.empty()) {
            const Everywhere e = everywhere(c);
            o["uniformity"] = number(e.uniformity);
            o["least_covered_region"] = e.least_covered >= 0
                                            ? nlohmann::ordered_json(c.regions.name(static_cast<std::size_t>(e.least_covered)))
                                            : nlohmann::ordered_json(nullptr);
            o["time_to_98_everywhere_s"] = number(e.time_to_98_s);
            o["time_to_98_everywhere_high_s"] = number(e.time_to_98_high_s);
        }
        components.push_back(std::move(o));
    }
    j["components"] = std::move(components);
    return j.dump(2) + "\n";
}

}  // namespace peensim
