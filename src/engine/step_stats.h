// Wall time spent in each named stage of a step (STYLE practice 1), for the benchmark and summary.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "common/cycle_clock.h"

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
    std::uint64_t bvh_sweeps_gated = 0;    // event scheme: BVH sweeps answered by the occupied cells (no walk)
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
    // Every counter, by name: the one list that adding another scheme's figures follows.
    template <class Visit>
    void for_each_counter(Visit&& visit) const {
        each_counter(*this, visit);
    }
    template <class Visit>
    void for_each_counter(Visit&& visit) {
        each_counter(*this, visit);
    }
    // Adds another scheme's figures (the event scheme's hand-over to time stepping): every stage
    // time and every counter.
    StepStats& operator+=(const StepStats& o) {
        for (std::size_t k = 0; k < seconds.size(); ++k) seconds[k] += o.seconds[k];
        std::array<std::uint64_t, kCounters> theirs{};
        std::size_t k = 0;
        o.for_each_counter([&](const char*, std::uint64_t v) { theirs[k++] = v; });
        k = 0;
        for_each_counter([&](const char*, std::uint64_t& mine) { mine += theirs[k++]; });
        return *this;
    }
    double& operator[](Stage s) { return seconds[static_cast<std::size_t>(s)]; }
    double operator[](Stage s) const { return seconds[static_cast<std::size_t>(s)]; }

    static constexpr std::size_t kCounters = 26;

private:
    template <class Self, class Visit>
    static void each_counter(Self& self, Visit& visit) {
        visit("gate_checks", self.gate_checks);
        visit("gate_skips", self.gate_skips);
        visit("memo_skips", self.memo_skips);
        visit("bvh_queries", self.bvh_queries);
        visit("bvh_hits", self.bvh_hits);
        visit("triangles_returned", self.triangles_returned);
        visit("triangle_tests", self.triangle_tests);
        visit("bvh_sweeps_gated", self.bvh_sweeps_gated);
        visit("touch_searches", self.touch_searches);
        visit("events", self.events);
        visit("stale_events", self.stale_events);
        visit("box_renewals", self.box_renewals);
        visit("pair_tests", self.pair_tests);
        visit("mesh_predictions", self.mesh_predictions);
        visit("rides", self.rides);
        visit("search_resumes", self.search_resumes);
        visit("grazes", self.grazes);
        visit("substeps", self.substeps);
        visit("sleeps", self.sleeps);
        visit("collapse_guards", self.collapse_guards);
        visit("hand_overs", self.hand_overs);
        visit("soft_steps", self.soft_steps);
        visit("soft_member_steps", self.soft_member_steps);
        visit("soft_contact_evaluations", self.soft_contact_evaluations);
        visit("soft_joins", self.soft_joins);
        visit("soft_rests", self.soft_rests);
    }
};

// Every counter is in the list: the counters are all the struct holds besides the stage times.
static_assert(sizeof(StepStats) ==
                  sizeof(std::array<double, static_cast<int>(Stage::count)>) + StepStats::kCounters * sizeof(std::uint64_t),
              "a StepStats counter is missing from each_counter (and kCounters)");

// Adds the wall time of its scope to one stage (read on the cycle clock: a scope may be a single
// prediction).
class StageTimer {
public:
    StageTimer(StepStats& stats, Stage stage) : stats_(stats), stage_(stage), start_(cycle_count()) {}
    ~StageTimer() { stats_[stage_] += static_cast<double>(cycle_count() - start_) * seconds_per_cycle(); }
    StageTimer(const StageTimer&) = delete;
    StageTimer& operator=(const StageTimer&) = delete;

private:
    StepStats& stats_;
    Stage stage_;
    std::uint64_t start_;  // cycle_count() ticks
};

}  // namespace peensim
