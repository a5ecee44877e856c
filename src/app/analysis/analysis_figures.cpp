#include "app/analysis/analysis_figures.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "analysis/region_stats.h"
#include "app/analysis/almen_analysis.h"
#include "app/analysis/coverage_verdict.h"
#include "output/json_number.h"

namespace peensim {

namespace {

// An area out of the shot's reach and the shot diameters that would reach half and 90 % of it.
nlohmann::ordered_json out_of_reach_json(const UnreachableArea& u) {
    return {{"area_m2", u.area_m2},
            {"half_reached_by_m", json_number(u.half_reached_by_m)},
            {"most_reached_by_m", json_number(u.most_reached_by_m)}};
}

// A forecast of the time to the target (s of peening since the window opened) with its status.
nlohmann::ordered_json forecast_json(const AreaForecast& f) {
    const bool timed = f.status == AreaForecast::Status::reached || f.status == AreaForecast::Status::forecast;
    nlohmann::ordered_json o;
    o["status"] = status_name(f.status);
    o["coverage_now"] = json_number(f.coverage_now);
    o["time_s"] = json_number(timed ? f.time_s : NAN);
    o["low_s"] = json_number(timed ? f.low_s : NAN);
    o["high_s"] = json_number(timed ? f.high_s : NAN);  // null: unbounded
    o["smoothing_bias_s"] = json_number(f.status == AreaForecast::Status::forecast ? f.bias_s : NAN);
    o["run_for_s"] = json_number(f.status == AreaForecast::Status::too_short ? f.run_for_s : NAN);
    if (f.seen_in_run) o["seen_in_run"] = true;  // reached after the window, as the run until coverage counted
    return o;
}

}  // namespace

std::string analysis_figures_json(const std::vector<ComponentAnalysis>& parts, const AnalysisWindow& window) {
    const double duration_s = window.length_s();
    nlohmann::ordered_json j;
    j["duration_s"] = duration_s;
    j["window"] = {{"from_s", window.from_s},
                   {"to_s", window.to_s},
                   {"min_speed_mps", window.min_speed_m_per_s},
                   {"turn_s", json_number(window.turn_s > 0.0 ? window.turn_s : NAN)},  // the rotating part's turn (null: none)
                   {"asked_to_s", window.asked_to_s},                                   // before the window was cut to whole turns
                   {"ends_at_target", window.ends_at_target}};                          // a run until coverage, kept to its end (not cut)
    j["target_coverage"] = window.target_coverage;
    j["batches"] = kFigureBatches;
    auto components = nlohmann::ordered_json::array();
    for (const ComponentAnalysis& c : parts) {
        nlohmann::ordered_json o;
        const double n = static_cast<double>(c.impacts);
        o["component"] = c.name;
        o["impacts"] = c.impacts;
        o["impact_rate_per_s"] = json_number(duration_s > 0.0 ? n / duration_s : NAN);
        o["mean_vn_mps"] = json_number(c.impacts ? c.speed_sum / n : NAN);
        o["mean_dent_m"] = json_number(c.impacts && c.coverage ? c.dent_sum / n : NAN);
        o["coverage"] = json_number(c.coverage ? c.coverage->coverage() : NAN);  // of the peened area
        if (c.coverage) {
            const PeenedAreas areas = peened_areas(c);
            o["area_m2"] = areas.total_m2;
            o["peened_area_m2"] = areas.peened_m2;
            o["unreachable_area_m2"] = areas.unreachable_m2;
            o["excluded_area_m2"] = areas.excluded_m2;
            o["share_below_target"] = json_number(share_below(c, window.target_coverage));
            o["time_to_target"] = forecast_json(c.forecast.whole);
            o["out_of_reach"] = out_of_reach_json(c.unreachable.whole);
            const ForecastSummary& f = c.forecast.summary;
            o["forecast"] = {{"radius_m", json_number(f.radius_m > 0.0 ? f.radius_m : NAN)},
                             {"rate_window_s", f.rate_window_s},
                             {"startup_left_out", f.startup_left_out},
                             {"rate_change", f.rate_change},
                             {"rate_drifts", f.rate_drifts},
                             {"everywhere_chance_excess_s", f.everywhere_chance_excess_s},
                             {"face_impacts", f.face_impacts},
                             {"edge_impacts", f.edge_impacts},
                             {"edge_lines", f.edge_lines}};
        }
        if (c.almen) add_almen_figures(o, *c.almen);
        // Batch means: each tenth of the window's impact rate and mean normal speed.
        auto rate = nlohmann::ordered_json::array(), speed = nlohmann::ordered_json::array();
        for (int b = 0; b < kFigureBatches; ++b) {
            const auto k = static_cast<std::size_t>(b);
            const double impacts = static_cast<double>(c.batch_impacts[k]);
            rate.push_back(json_number(duration_s > 0.0 ? impacts / (duration_s / kFigureBatches) : NAN));
            speed.push_back(json_number(impacts > 0.0 ? c.batch_speed_sum[k] / impacts : NAN));
        }
        o["batch_impact_rate_per_s"] = std::move(rate);
        o["batch_mean_vn_mps"] = std::move(speed);
        auto regions = nlohmann::ordered_json::array();
        for (std::size_t r = 0; r < c.regions.size(); ++r) {
            const RegionStats x = region_stats(c.regions, r, c.region_tallies[r], c.coverage.get(), duration_s);
            nlohmann::ordered_json g{
                {"region", c.regions.name(r)},
                {"excluded", c.regions.excluded(r)},
                {"area_m2", x.area_m2},
                {"peened_area_m2", json_number(x.peened_area_m2)},
                {"unreachable_area_m2", json_number(x.unreachable_area_m2)},
                {"impacts", x.impacts},
                {"impact_rate_per_s", json_number(duration_s > 0.0 ? static_cast<double>(x.impacts) / duration_s : NAN)},
                {"mean_vn_mps", json_number(x.mean_normal_speed)},
                {"coverage", json_number(x.coverage)}};
            if (c.coverage && r < c.forecast.regions.size()) g["time_to_target"] = forecast_json(c.forecast.regions[r]);
            if (c.coverage && r < c.unreachable.regions.size()) g["out_of_reach"] = out_of_reach_json(c.unreachable.regions[r]);
            regions.push_back(std::move(g));
        }
        o["regions"] = std::move(regions);
        if (c.coverage) {
            const Everywhere e = everywhere(c);
            o["time_to_target_everywhere"] = forecast_json(e.time);
            const std::string slowest = slowest_area_name(c, e.slowest);
            o["slowest_region"] = slowest.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(slowest);
            o["uniformity"] = {
                {"value", json_number(e.uniformity)}, {"low", json_number(e.uniformity_low)}, {"high", json_number(e.uniformity_high)}};
        }
        components.push_back(std::move(o));
    }
    j["components"] = std::move(components);
    return j.dump(2) + "\n";
}

}  // namespace peensim
