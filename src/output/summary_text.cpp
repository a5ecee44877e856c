#include "output/summary_text.h"

#include <cmath>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace peensim {
namespace {

std::string printf_string(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

std::string printf_string(const char* fmt, ...) {
    char line[512];
    va_list args;
    va_start(args, fmt);
    std::vsnprintf(line, sizeof line, fmt, args);
    va_end(args);
    return line;
}

std::string speeds_text(const NormalSpeedStats& n) {
    if (n.count == 0) return "no impacts";
    return printf_string("vn mean %.3f m/s  p10 %.3f  p50 %.3f  p90 %.3f  max %.3f m/s", n.mean_m_per_s, n.p10_m_per_s, n.p50_m_per_s,
                         n.p90_m_per_s, n.max_m_per_s);
}

std::string health_text(const std::vector<NamedCount>& counters) {
    std::string text;
    for (const auto& c : counters) {
        if (c.count == 0) continue;
        if (!text.empty()) text += ", ";
        text += c.name + " " + std::to_string(c.count);
    }
    return text.empty() ? "all zero" : text;
}

// Landings slower than the impact speed (sustained contact, not impacts), non-zero ones only.
std::string slow_contacts_text(const std::vector<NamedCount>& counts, double impact_speed_m_per_s) {
    std::string text;
    for (const auto& c : counts) {
        if (c.count == 0) continue;
        if (!text.empty()) text += ", ";
        text += c.name + " " + std::to_string(c.count);
    }
    return (text.empty() ? std::string("none") : text) + printf_string(" (landings slower than %.3g m/s)", impact_speed_m_per_s);
}

// "0 placed + 1000 emitted (nozzle 1000) = 940 collected (away 940) + 0 lost + 60 in flight + 0 at rest".
std::string flow_text(const RunSummary& s) {
    const auto listed = [](const std::vector<NamedCount>& counts) {
        std::uint64_t total = 0;
        std::string names;
        for (const auto& c : counts) {
            total += c.count;
            names += (names.empty() ? "" : ", ") + c.name + " " + std::to_string(c.count);
        }
        return std::to_string(total) + (counts.empty() ? std::string() : " (" + names + ")");
    };
    return std::to_string(s.shot_count) + " placed + " + listed(s.emitted_per_source) + " emitted = " + listed(s.collected_per_sink) +
           " collected + " + std::to_string(s.shot_lost) + " lost + " + std::to_string(s.shots_in_flight) + " in flight + " +
           std::to_string(s.shots_at_rest) + " at rest";
}

}  // namespace

std::string summary_to_text(const RunSummary& s) {
    std::vector<std::pair<std::string, std::string>> rows;  // label, value
    rows.reserve(24);  // (also keeps GCC 12's -Warray-bounds from a false alarm on the first emplace into an empty vector)
    rows.emplace_back("simulated",
                      printf_string("%.6g s of %.6g s (%s)", s.simulated_time_s, s.duration_s, s.finished ? "finished" : "interrupted"));
    rows.emplace_back("wall time", printf_string("%.3f s (%.4g simulated s per wall s)", s.wall_time_s, s.sim_seconds_per_wall_second));
    if (s.until_coverage) {
        // Until coverage: reached where, when; the slowest area last, or the least covered one
        // not there yet (the first of them in the list may be nearly there).
        double last = 0.0, least = INFINITY;
        std::string slowest, missing;
        int reached = 0;
        for (const auto& a : s.until_coverage->areas) {
            if (std::isfinite(a.reached_at_s)) {
                ++reached;
                if (a.reached_at_s >= last) last = a.reached_at_s, slowest = a.name;
            } else if (a.coverage < least) {
                least = a.coverage;
                missing = a.name + printf_string(" at %.4g %%", 100.0 * a.coverage);
            }
        }
        const double target = 100.0 * s.until_coverage->target;
        rows.emplace_back(
            "until coverage",
            s.until_coverage->reached
                ? printf_string("%.4g %% reached everywhere watched (%d area%s) at %.6g s, last %s", target, reached,
                                reached == 1 ? "" : "s", last, slowest.c_str())
                : printf_string("%.4g %% reached in %d of %zu areas%s; not yet: %s%s", target, reached, s.until_coverage->areas.size(),
                                // A finished run that did not reach it stopped at its cap: a scene's
                                // duration is often a quick look's, which the user may not have meant.
                                s.finished ? printf_string(" by the cap, process.duration = %.6g s (raise it with --set "
                                                           "\"process.duration=...\")",
                                                           s.duration_s)
                                                 .c_str()
                                           : "",
                                missing.c_str(), reached + 1 < static_cast<int>(s.until_coverage->areas.size()) ? ", ..." : ""));
    }
    if (s.replicas && s.replicas->round_s > 0.0) {
        // The others log from the warm-up on, rounded up to the part's angle at their first slot.
        double from_s = std::numeric_limits<double>::infinity(), to_s = 0.0;
        std::vector<bool> seen(static_cast<std::size_t>(std::max(1, s.replicas->replica_count)), false);
        for (const auto& w : s.replicas->windows) {
            const auto k = static_cast<std::size_t>(w.replica);
            if (w.replica <= 0 || k >= seen.size() || seen[k]) continue;
            seen[k] = true;
            from_s = std::min(from_s, w.own_start_s);
            to_s = std::max(to_s, w.own_start_s);
        }
        std::string others = printf_string("a warm-up of %.4g s measured at %.4g s", s.replicas->warm_up_s, s.replicas->pilot_s);
        if (std::isfinite(from_s))
            others += from_s == to_s ? printf_string("; the others log from their own %.4g s on", from_s)
                                     : printf_string("; the others log from their own %.4g-%.4g s on", from_s, to_s);
        rows.emplace_back("replicas", printf_string("%d in rounds of %.4g s (%zu slots logged), ", s.replicas->replica_count,
                                                    s.replicas->round_s, s.replicas->windows.size()) +
                                          others);
    } else if (s.replicas)
        rows.emplace_back(
            "replicas",
            printf_string("%zu, each warmed up %.4g s (measured at %.4g s) then run for its window of %.4g s", s.replicas->windows.size(),
                          s.replicas->warm_up_s, s.replicas->pilot_s,
                          s.replicas->windows.size() > 1 ? s.replicas->windows[1].end_s - s.replicas->windows[1].start_s : s.duration_s));
    // Flights other than the exact parabola (air drag) run with time stepping only: say why.
    if (!s.flight.empty() && s.flight != "parabola")
        rows.emplace_back("flight", s.flight + " (time stepping: the event scheme solves exact parabolas only)");
    if (s.scheme == "event")  // shot_steps counts events, steps the times the state was brought up to date
        rows.emplace_back("events", printf_string("%.4g (%.4g per wall s)", static_cast<double>(s.shot_steps), s.shot_steps_per_s));
    else
        rows.emplace_back("steps", printf_string("%llu (%.4g shot steps, %.4g per s)", static_cast<unsigned long long>(s.steps),
                                                 static_cast<double>(s.shot_steps), s.shot_steps_per_s));
    if (s.emitted_per_source.empty() && s.collected_per_sink.empty())
        rows.emplace_back("shots", printf_string("%llu (%llu lost)", static_cast<unsigned long long>(s.shot_count),
                                                 static_cast<unsigned long long>(s.shot_lost)));
    else
        rows.emplace_back("shots", flow_text(s));
    for (const auto& [name, eps] : s.flow_rate_eps)
        rows.emplace_back("flow " + name, printf_string("eps = r_m D / (v0 m_shot) = %.4g", eps));
    if (s.shot_sizes.size() > 1) {  // a mix: what it came out as beside what the scene asked
        std::uint64_t total = 0;
        for (const auto& z : s.shot_sizes) total += z.shots;
        std::string value;
        for (const auto& z : s.shot_sizes)
            value += (value.empty() ? "" : ", ") +
                     printf_string(
                         "%.4g mm %llu (%.1f %% of the count, asked %.1f %%)", z.diameter_m * 1e3, static_cast<unsigned long long>(z.shots),
                         total > 0 ? 100.0 * static_cast<double>(z.shots) / static_cast<double>(total) : 0.0, 100.0 * z.count_fraction);
        rows.emplace_back("shot sizes", value);
    }
    for (const auto& c : s.impacts_per_component) {
        std::string value = std::to_string(c.count);
        const auto stats =
            std::find_if(s.normal_speed.begin(), s.normal_speed.end(), [&](const NormalSpeedStats& n) { return n.component == c.name; });
        if (stats != s.normal_speed.end() && stats->count > 0) value += "  " + speeds_text(*stats);
        rows.emplace_back("impacts " + c.name, std::move(value));
    }
    rows.emplace_back("slow contacts", slow_contacts_text(s.slow_contacts_per_component, s.impact_speed_m_per_s));
    for (const auto& [component, text] : s.law_states) rows.emplace_back("law " + component, text);
    rows.emplace_back("health", health_text(s.health_counters));
    if (const auto& f = s.first_search_fallback; f.shot >= 0)
        rows.emplace_back(
            "search fallback",
            printf_string("first at t = %.6g s: shot %d near '%s' at (%.3f, %.3f, %.3f) mm, its exact contact search gaining no "
                          "time; it went on in sustained-contact substeps",
                          f.time_s, f.shot, f.component.c_str(), 1e3 * f.position_m[0], 1e3 * f.position_m[1], 1e3 * f.position_m[2]));
    rows.emplace_back("peak memory", printf_string("%.1f MiB", static_cast<double>(s.peak_memory_bytes) / (1024.0 * 1024.0)));

    std::size_t width = 0;
    for (const auto& row : rows) width = std::max(width, row.first.size());
    std::string text = "peensim " + s.scene_file + "\n";
    for (const auto& [label, value] : rows) {
        text += "  " + label + std::string(width - label.size() + 2, ' ') + value + '\n';
    }
    return text;
}

}  // namespace peensim
