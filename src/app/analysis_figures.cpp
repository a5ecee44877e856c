#include "app/analysis_figures.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "analysis/avrami.h"
#include "analysis/region_stats.h"
#include "app/almen_analysis.h"

namespace peensim {

namespace {

// JSON has no NaN: a figure that does not exist is null.
nlohmann::ordered_json number(double x) { return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr); }

}  // namespace

std::string analysis_figures_json(const std::vector<ComponentAnalysis>& parts, double duration_s) {
    nlohmann::ordered_json j;
    j["duration_s"] = duration_s;
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
        o["coverage"] = number(c.coverage ? c.coverage->coverage() : NAN);
        if (c.coverage) {
            const AvramiFit fit = fit_avrami(c.curve);
            const bool fitted = fit.points_used > 0 && fit.k_per_s > 0.0;
            o["avrami_k_per_s"] = number(fitted ? fit.k_per_s : NAN);
            o["avrami_k_se_per_s"] = number(fitted ? fit.k_standard_error_per_s : NAN);
            o["time_to_98_s"] = number(fitted ? fit.time_to_98_percent_s : NAN);
            o["time_to_98_extrapolated"] = fitted && fit.extrapolated;
        }
        if (c.almen) add_almen_figures(o, *c.almen);
        // Batch means: each tenth of the run's impact rate and mean normal speed.
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
        for (const Region& region : c.regions) {
            const RegionStats r = region_stats(region, *c.fields, c.coverage.get(), duration_s);
            regions.push_back({{"region", region.name},
                               {"impacts", r.impacts},
                               {"impact_rate_per_s", number(duration_s > 0.0 ? static_cast<double>(r.impacts) / duration_s : NAN)},
                               {"mean_vn_mps", number(r.mean_normal_speed)},
                               {"coverage", number(r.coverage)}});
        }
        o["regions"] = std::move(regions);
        components.push_back(std::move(o));
    }
    j["components"] = std::move(components);
    return j.dump(2) + "\n";
}

}  // namespace peensim
