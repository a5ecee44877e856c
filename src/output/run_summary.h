// What a run reports when it ends (or is interrupted): the numbers behind summary.json and
// the few lines printed to the terminal. Plain values; the engine and the CLI fill it in.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "output/speed_histogram.h"

namespace peensim {

struct NamedCount {
    std::string name;
    std::uint64_t count = 0;
};

// Normal approach speeds of the impacts on one logged component.
struct NormalSpeedStats {
    std::string component;
    std::uint64_t count = 0;
    double mean_m_per_s = 0.0;  // m/s; NaN when count == 0 (null in JSON)
    double p10_m_per_s = 0.0;   // m/s, 10th percentile (within one histogram bin)
    double p50_m_per_s = 0.0;   // m/s, median
    double p90_m_per_s = 0.0;   // m/s, 90th percentile
    double max_m_per_s = 0.0;   // m/s, exact
};

NormalSpeedStats normal_speed_stats(std::string component, const SpeedHistogram& speeds);

// Wall time spent in one named stage of the step (e.g. "detectContacts").
struct StageTime {
    std::string stage;
    double seconds = 0.0;  // s, wall time summed over all steps
};

struct RunSummary {
    std::string scene_file;              // path as the user gave it
    std::vector<std::string> overrides;  // the --set options, as given ("path=value"), in order
    std::string scene_hash;              // hex digest of the scene and everything it references
    std::string scheme;                  // time-integration scheme name
    std::string flight;                  // flight model between contacts ("parabola", "air drag")
    bool finished = false;               // false when the run was interrupted (Ctrl-C, --max-wall-time)

    double simulated_time_s = 0.0;  // s, simulated time reached
    double duration_s = 0.0;        // s, simulated time the scene asked for
    double wall_time_s = 0.0;       // s, wall-clock time of the run
    std::uint64_t steps = 0;
    std::uint64_t shot_steps = 0;              // steps x shots in flight, summed
    double shot_steps_per_s = 0.0;             // 1/s of wall time
    double sim_seconds_per_wall_second = 0.0;  // simulated s per wall s

    std::uint64_t shot_count = 0;
    std::uint64_t shot_lost = 0;  // shots that left the chamber or went non-finite

    // Shot sources and sinks (empty without): shot each emitted, and each collected.
    std::vector<NamedCount> emitted_per_source;
    std::vector<NamedCount> collected_per_sink;
    // The mass balance at the end: placed + emitted = collected + lost + in flight + at rest (the
    // shot still in the run, slower than the impact speed: at rest).
    std::uint64_t shots_in_flight = 0;
    std::uint64_t shots_at_rest = 0;
    // Per source: its dimensionless flow rate eps = r_m D / (v0 m_shot) (the conventional-peening
    // study's measure of how crowded the jet is; r_m the mass flow, kg/s).
    std::vector<std::pair<std::string, double>> flow_rate_eps;
    // The shot's sizes (one, or a mix): each one's diameter, its share of the count and of the mass
    // the scene asked for, and how many shot of it were placed and emitted.
    struct ShotSizeCount {
        double diameter_m = 0.0;
        double count_fraction = 1.0;
        double mass_fraction = 1.0;
        std::uint64_t shots = 0;
    };
    std::vector<ShotSizeCount> shot_sizes;
    std::vector<NamedCount> impacts_per_component;
    // Flights that ended in sustained contact (approach slower than impact_speed_m_per_s): not
    // impacts, counted once per landing; same entries as impacts_per_component.
    std::vector<NamedCount> slow_contacts_per_component;
    double impact_speed_m_per_s = 0.0;           // m/s, the scene's accuracy.impact_speed
    std::vector<NormalSpeedStats> normal_speed;  // per logged component
    // Per component whose contact law keeps state: the law's one-line account of it (text summary).
    std::vector<std::pair<std::string, std::string>> law_states;
    std::vector<NamedCount> health_counters;
    // The first search fallback (health counter search_fallbacks): when, which shot, near which
    // component, where (m, world); shot < 0: none.
    struct SearchFallbackAt {
        double time_s = 0.0;
        int shot = -1;
        std::string component;
        double position_m[3] = {0.0, 0.0, 0.0};
    } first_search_fallback;
    std::vector<StageTime> stage_times;  // in step order

    std::uint64_t peak_memory_bytes = 0;  // bytes, peak resident set size

    // A run until coverage (process.until_coverage): the target, and each watched area's coverage
    // now and when it reached the target (NaN: not yet).
    struct CoverageGoal {
        double target = 0.98;
        struct Area {
            std::string name;
            double reached_at_s = 0.0;  // s of simulated time (NaN: not yet)
            double coverage = 0.0;      // 0..1
        };
        std::vector<Area> areas;
        bool reached = false;  // every area reached it (the run ended there, before the duration)
    };
    std::optional<CoverageGoal> until_coverage;
    // A run on several cores as replicas (run --replicas, app/run/replica_plan.h): the measured
    // start-up transient and each replica's window of the run.
    struct Replicas {
        double pilot_s = 0.0;    // s, replica 0's time when the warm-up was measured
        double warm_up_s = 0.0;  // s, the start-up transient MSER-5 found
        double turn_s = 0.0;     // s, the part's turn the windows are shifted by whole numbers of (0: none)
        // Until coverage (replica_rounds.h): the replicas' slots after replica 0's first (0: one
        // window a replica), and how many replicas ran them.
        double round_s = 0.0;  // s
        int replica_count = 0;
        struct Window {
            int replica = 0;
            std::uint64_t seed = 0;
            double start_s = 0.0;      // s, run time: the window is [start_s, end_s)
            double end_s = 0.0;        // s
            double own_start_s = 0.0;  // s, the window's start in the replica's own time (its warm-up)
            std::uint64_t logged_impacts = 0;
        };
        std::vector<Window> windows;
    };
    std::optional<Replicas> replicas;
};

}  // namespace peensim
