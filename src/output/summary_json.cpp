#include "output/summary_json.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "output/atomic_file.h"

namespace peensim {

std::string summary_to_json(const RunSummary& s) {
    // ordered_json keeps the keys in the documented order, which reads better than sorted.
    nlohmann::ordered_json j;
    j["scene_file"] = s.scene_file;
    j["scene_hash"] = s.scene_hash;
    j["overrides"] = s.overrides;
    j["scheme"] = s.scheme;
    j["flight"] = s.flight;
    j["finished"] = s.finished;
    j["simulated_time_s"] = s.simulated_time_s;
    j["duration_s"] = s.duration_s;
    j["wall_time_s"] = s.wall_time_s;
    j["steps"] = s.steps;
    j["shot_steps"] = s.shot_steps;
    j["shot_steps_per_s"] = s.shot_steps_per_s;
    j["sim_seconds_per_wall_second"] = s.sim_seconds_per_wall_second;
    j["shot_count"] = s.shot_count;
    j["shot_lost"] = s.shot_lost;
    if (s.until_coverage) {
        // JSON has no NaN: an area not reached yet has null.
        auto areas = nlohmann::ordered_json::array();
        for (const auto& a : s.until_coverage->areas)
            areas.push_back({{"area", a.name},
                             {"coverage", a.coverage},
                             {"reached_at_s",
                              std::isfinite(a.reached_at_s) ? nlohmann::ordered_json(a.reached_at_s) : nlohmann::ordered_json(nullptr)}});
        j["until_coverage"] = {{"target", s.until_coverage->target}, {"reached", s.until_coverage->reached}, {"areas", std::move(areas)}};
    }
    if (s.replicas) {
        auto windows = nlohmann::ordered_json::array();
        for (const auto& w : s.replicas->windows)
            windows.push_back({{"replica", w.replica},
                               {"seed", w.seed},
                               {"start_s", w.start_s},
                               {"end_s", w.end_s},
                               {"own_start_s", w.own_start_s},
                               {"logged_impacts", w.logged_impacts}});
        j["replicas"] = {{"pilot_s", s.replicas->pilot_s}, {"warm_up_s", s.replicas->warm_up_s}, {"turn_s", s.replicas->turn_s}};
        if (s.replicas->round_s > 0.0) {  // until coverage: in rounds
            j["replicas"]["replicas"] = s.replicas->replica_count;
            j["replicas"]["round_s"] = s.replicas->round_s;
        }
        j["replicas"]["windows"] = std::move(windows);
    }

    auto impacts = nlohmann::ordered_json::array();
    for (const auto& c : s.impacts_per_component) {
        impacts.push_back({{"component", c.name}, {"impacts", c.count}});
    }
    j["impacts_per_component"] = std::move(impacts);

    auto slow = nlohmann::ordered_json::array();
    for (const auto& c : s.slow_contacts_per_component) slow.push_back({{"component", c.name}, {"slow_contacts", c.count}});
    j["slow_contacts_per_component"] = std::move(slow);
    auto emitted = nlohmann::ordered_json::array(), collected = nlohmann::ordered_json::array();
    for (const auto& c : s.emitted_per_source) emitted.push_back({{"source", c.name}, {"emitted", c.count}});
    for (const auto& c : s.collected_per_sink) collected.push_back({{"sink", c.name}, {"collected", c.count}});
    j["emitted_per_source"] = std::move(emitted);
    j["collected_per_sink"] = std::move(collected);
    j["shots_in_flight"] = s.shots_in_flight;
    j["shots_at_rest"] = s.shots_at_rest;
    auto eps = nlohmann::ordered_json::array();
    for (const auto& [name, value] : s.flow_rate_eps) eps.push_back({{"source", name}, {"eps", value}});
    j["flow_rate_eps"] = std::move(eps);
    auto sizes = nlohmann::ordered_json::array();
    for (const RunSummary::ShotSizeCount& z : s.shot_sizes)
        sizes.push_back(
            {{"diameter_m", z.diameter_m}, {"count_fraction", z.count_fraction}, {"mass_fraction", z.mass_fraction}, {"shots", z.shots}});
    j["shot_sizes"] = std::move(sizes);
    j["impact_speed_mps"] = s.impact_speed_m_per_s;

    auto speeds = nlohmann::ordered_json::array();
    for (const auto& n : s.normal_speed) {
        speeds.push_back({{"component", n.component},
                          {"count", n.count},
                          {"mean_normal_speed_mps", n.mean_m_per_s},
                          {"p10_normal_speed_mps", n.p10_m_per_s},
                          {"p50_normal_speed_mps", n.p50_m_per_s},
                          {"p90_normal_speed_mps", n.p90_m_per_s},
                          {"max_normal_speed_mps", n.max_m_per_s}});
    }
    j["normal_speed"] = std::move(speeds);

    auto health = nlohmann::ordered_json::object();
    for (const auto& h : s.health_counters) health[h.name] = h.count;
    j["health_counters"] = std::move(health);
    if (const auto& f = s.first_search_fallback; f.shot >= 0)
        j["first_search_fallback"] = {{"time_s", f.time_s},
                                      {"shot", f.shot},
                                      {"component", f.component},
                                      {"position_m", {f.position_m[0], f.position_m[1], f.position_m[2]}}};

    auto stages = nlohmann::ordered_json::object();
    for (const auto& t : s.stage_times) stages[t.stage] = t.seconds;
    j["step_stage_time_s"] = std::move(stages);

    j["peak_memory_bytes"] = s.peak_memory_bytes;
    // Paths and names are the user's bytes: replace invalid UTF-8 rather than fail the report.
    return j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + '\n';
}

void write_summary(const std::string& path, const RunSummary& summary) { write_file_atomically(path, summary_to_json(summary)); }

}  // namespace peensim
