#include "app/run/summary_builder.h"

#include <cstdio>

#include "output/peak_memory.h"

namespace peensim {

std::string scene_hash_text(const Model& model) { return scene_hash_hex(model.scene_hash); }

RunSummary build_summary(const Simulation& sim, const std::string& scene_file, const std::vector<SpeedHistogram>& normal_speeds,
                         double wall_time_s, bool finished) {
    const Model& model = sim.model();
    const SimulationState& state = sim.state();
    RunSummary s;
    s.scene_file = scene_file;
    s.scene_hash = scene_hash_text(model);
    s.scheme = std::string(sim.scheme().name());
    s.flight = std::string(model.flight->name());
    s.finished = finished;
    s.simulated_time_s = state.time.seconds();
    s.duration_s = model.duration_s;
    s.wall_time_s = wall_time_s;
    s.steps = state.steps;
    s.shot_steps = state.shot_steps;
    s.shot_steps_per_s = wall_time_s > 0.0 ? static_cast<double>(state.shot_steps) / wall_time_s : 0.0;
    s.sim_seconds_per_wall_second = wall_time_s > 0.0 ? s.simulated_time_s / wall_time_s : 0.0;
    s.shot_count = static_cast<std::uint64_t>(model.shot_count);
    s.shot_lost = state.health.shot_lost + state.health.non_finite;
    for (std::size_t k = 0; k < model.sources.size() && k < state.emitted_per_source.size(); ++k)
        s.emitted_per_source.push_back({model.sources[k]->name(), state.emitted_per_source[k]});
    for (std::size_t k = 0; k < model.sinks.size() && k < state.collected_per_sink.size(); ++k)
        s.collected_per_sink.push_back({model.sinks[k]->name(), state.collected_per_sink[k]});
    for (std::size_t i = 0; i < state.shots.size(); ++i) {
        if (!state.shots.active[i]) continue;
        if (state.shots.velocity(i).norm() < model.impact_speed_m_per_s)
            ++s.shots_at_rest;
        else
            ++s.shots_in_flight;
    }
    // A mix's eps counts its mean diameter (by count): shot per diameter travelled.
    double mean_diameter = 0.0, mean_mass = 0.0;
    for (const ShotSize& size : model.shot_sizes) {
        mean_diameter += size.count_fraction * 2.0 * size.radius_m;
        mean_mass += size.count_fraction * size.mass_kg;
    }
    for (std::size_t k = 0; k < model.shot_sizes.size(); ++k) {
        const ShotSize& size = model.shot_sizes[k];
        s.shot_sizes.push_back({2.0 * size.radius_m, size.count_fraction, size.count_fraction * size.mass_kg / mean_mass,
                                k < state.shots_per_size.size() ? state.shots_per_size[k] : 0});
    }
    for (const auto& source : model.sources)
        if (const SourceOutline o = source->outline(); o.jet)
            s.flow_rate_eps.emplace_back(source->name(), jet_flow_rate_eps(o.rate_per_s, *o.jet, mean_diameter));
    s.impacts_per_component.push_back({"shot-shot", state.shot_shot_impacts});
    s.slow_contacts_per_component.push_back({"shot-shot", state.shot_shot_slow_contacts});
    s.impact_speed_m_per_s = model.impact_speed_m_per_s;
    std::size_t logged = 0;
    for (std::size_t c = 0; c < model.components.size(); ++c) {
        s.impacts_per_component.push_back({model.components[c].name, state.impacts_per_component[c]});
        const std::uint64_t slow = c < state.slow_contacts_per_component.size() ? state.slow_contacts_per_component[c] : 0;
        s.slow_contacts_per_component.push_back({model.components[c].name, slow});
        if (model.components[c].logged && logged < normal_speeds.size())
            s.normal_speed.push_back(normal_speed_stats(model.components[c].name, normal_speeds[logged++]));
    }
    for (std::size_t c = 0; c < model.components.size() && c < state.law_state.size(); ++c) {
        const std::string text = model.components[c].law->describe_state(state.law_state[c]);
        if (!text.empty()) s.law_states.emplace_back(model.components[c].name, std::string(model.components[c].law->name()) + ": " + text);
    }
    state.health.for_each([&](const char* name, std::uint64_t count) { s.health_counters.push_back({name, count}); });
    if (const SearchFallback& f = state.first_search_fallback; f.time_s >= 0.0) {
        s.first_search_fallback.time_s = f.time_s;
        s.first_search_fallback.shot = f.shot;
        const auto c = static_cast<std::size_t>(f.component);
        s.first_search_fallback.component = f.component >= 0 && c < model.components.size() ? model.components[c].name : "?";
        for (int k = 0; k < 3; ++k) s.first_search_fallback.position_m[k] = f.position_m[k];
    }
    const StepStats& stats = sim.scheme().stats();
    for (std::size_t k = 0; k < kStageNames.size(); ++k) s.stage_times.push_back({std::string(kStageNames[k]), stats.seconds[k]});
    s.peak_memory_bytes = peak_resident_bytes();
    return s;
}

}  // namespace peensim
