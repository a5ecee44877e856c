// Wall time spent in each named stage of a step (STYLE practice 1), for the benchmark and summary.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <string_view>
#include <utility>

namespace peensim {

enum class Stage : int {
    kinematics,
    integrate,
    shot_broadphase,
    shot_contacts,
    mesh_queries,
    contact_laws,
    health,
    output,
    soft_contacts,
    count
};

constexpr std::array<std::string_view, static_cast<int>(Stage::count)> kStageNames{
    "advance_kinematics", "integrate_shots", "shot_broadphase", "shot_shot_contacts", "mesh_queries",
    "contact_laws",       "check_health",    "record_impacts",  "soft_contacts"};

struct StepStats {
    std::array<double, static_cast<int>(Stage::count)> seconds{};  // s of wall time per stage
    // Work counters, to see why a stage costs what it does.
    std::uint64_t gate_checks = 0;         // distance-gate look-ups (shot x component)
    std::uint64_t gate_skips = 0;          // shot x component checks skipped by the per-shot skip counters
    std::uint64_t memo_skips = 0;          // queries avoided by a shot's last measured distance
    std::uint64_t bvh_queries = 0;         // Bullet BVH queries
    std::uint64_t bvh_hits = 0;            // queries that found a triangle within reach
    std::uint64_t triangles_returned = 0;  // triangles the BVH returned
    std::uint64_t triangle_tests = 0;      // exact closest-point tests (after the plane test)
    std::uint64_t touch_searches = 0;      // touch-time searches (quadratic or sampled)
    // Event-driven scheme (zero for time stepping).
    std::uint64_t events = 0;            // events taken from the queue
    std::uint64_t stale_events = 0;      // pair events whose partner had changed flight since (re-predicted)
    std::uint64_t box_renewals = 0;      // search windows (and neighbour boxes) renewed at their end
    std::uint64_t pair_tests = 0;        // exact shot-shot time-of-impact tests
    std::uint64_t mesh_predictions = 0;  // shot x component time-of-impact searches
    std::uint64_t rides = 0;             // shot that rode the sonotrode after a slow rebound
    std::uint64_t search_resumes = 0;    // moving-mesh searches out of iterations, resumed by an event
    std::uint64_t grazes = 0;            // touches without approach on a surface that does not press the shot (flight goes on)
    std::uint64_t substeps = 0;          // sustained-contact substeps (resting, rolling, sliding shot)
    std::uint64_t sleeps = 0;            // shot put to sleep at rest
    std::uint64_t collapse_guards = 0;   // shot-shot collisions made elastic by the TC rule
    std::uint64_t hand_overs = 0;        // restart intervals handed over to time stepping (a load at rest)
    // Soft scheme (engine/soft/soft_pool.h).
    std::uint64_t soft_steps = 0;                // steps of the pool of shot in soft contact
    std::uint64_t soft_member_steps = 0;         // members advanced, summed over the steps
    std::uint64_t soft_contact_evaluations = 0;  // contact forces evaluated, summed over the steps
    std::uint64_t soft_joins = 0;                // shot taken into the pool
    std::uint64_t soft_rests = 0;                // members left to rigid sustained contact (slow contacts)
    // Adds another scheme's figures (the event scheme's hand-over to time stepping): every stage
    // time and every counter (a counter added to StepStats must be added here too).
    StepStats& operator+=(const StepStats& o) {
        for (std::size_t k = 0; k < seconds.size(); ++k) seconds[k] += o.seconds[k];
        for (auto [mine, theirs] : {std::pair{&gate_checks, &o.gate_checks},
                                    {&gate_skips, &o.gate_skips},
                                    {&memo_skips, &o.memo_skips},
                                    {&bvh_queries, &o.bvh_queries},
                                    {&bvh_hits, &o.bvh_hits},
                                    {&triangles_returned, &o.triangles_returned},
                                    {&triangle_tests, &o.triangle_tests},
                                    {&touch_searches, &o.touch_searches},
                                    {&events, &o.events},
                                    {&stale_events, &o.stale_events},
                                    {&box_renewals, &o.box_renewals},
                                    {&pair_tests, &o.pair_tests},
                                    {&mesh_predictions, &o.mesh_predictions},
                                    {&rides, &o.rides},
                                    {&search_resumes, &o.search_resumes},
                                    {&grazes, &o.grazes},
                                    {&substeps, &o.substeps},
                                    {&sleeps, &o.sleeps},
                                    {&collapse_guards, &o.collapse_guards},
                                    {&hand_overs, &o.hand_overs},
                                    {&soft_steps, &o.soft_steps},
                                    {&soft_member_steps, &o.soft_member_steps},
                                    {&soft_contact_evaluations, &o.soft_contact_evaluations},
                                    {&soft_joins, &o.soft_joins},
                                    {&soft_rests, &o.soft_rests}})
            *mine += *theirs;
        return *this;
    }
    double& operator[](Stage s) { return seconds[static_cast<std::size_t>(s)]; }
    double operator[](Stage s) const { return seconds[static_cast<std::size_t>(s)]; }
};

// Adds the wall time of its scope to one stage.
class StageTimer {
public:
    StageTimer(StepStats& stats, Stage stage) : stats_(stats), stage_(stage), start_(std::chrono::steady_clock::now()) {}
    ~StageTimer() { stats_[stage_] += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
    StageTimer(const StageTimer&) = delete;
    StageTimer& operator=(const StageTimer&) = delete;

private:
    StepStats& stats_;
    Stage stage_;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace peensim
