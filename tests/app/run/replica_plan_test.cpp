// The replicas' windows (app/run/replica_plan.h): they tile the run's time exactly, each replica
// warms up at least the measured transient, a rotating part's windows are shifted by whole turns,
// and all replicas end together (equal speed); scenes that are not steady are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "app/run/replica_plan.h"
#include "app/run/replica_rounds.h"
#include "model/model.h"
#include "scene/scene_parser.h"

namespace peensim {
namespace {

void expect_tiles(const ReplicaPlan& plan, double duration_s) {
    ASSERT_GE(plan.windows.size(), 2u);
    EXPECT_EQ(plan.windows.front().window_start_s(), 0.0);
    for (std::size_t k = 1; k < plan.windows.size(); ++k)
        EXPECT_NEAR(plan.windows[k].window_start_s(), plan.windows[k - 1].window_end_s(), 1e-12 * duration_s) << k;
    EXPECT_NEAR(plan.windows.back().window_end_s(), duration_s, 1e-12 * duration_s);
}

TEST(ReplicaPlan, WindowsTileTheRunAndEndTogether) {
    // T = 60 s, K = 4, pilot 1.5 s, warm-up 0.2 s: T0 = (60 + 3 * 1.5 + 3 * 0.2) / 4 = 16.275 s, and
    // every other replica runs 0.2 s + (T0 - P - W) = T0 - P of its own time.
    const auto plan = plan_replicas(60.0, 4, 1.5, 0.2, 0.0, 11);
    ASSERT_TRUE(plan.has_value());
    expect_tiles(*plan, 60.0);
    EXPECT_NEAR(plan->windows[0].run_to_s, 16.275, 1e-12);
    EXPECT_EQ(plan->windows[0].seed, 11u);
    for (std::size_t k = 1; k < 4; ++k) {
        const ReplicaWindow& w = plan->windows[k];
        EXPECT_DOUBLE_EQ(w.log_from_s, 0.2);
        EXPECT_NEAR(w.run_to_s, 16.275 - 1.5, 1e-12) << k;
        EXPECT_EQ(w.seed, replica_seed(11, static_cast<int>(k)));
        EXPECT_NE(w.seed, 11u);
    }
}

TEST(ReplicaPlan, ARotatingPartsWindowsShiftByWholeTurns) {
    const double turn = 2.0;  // 30 rpm
    const auto plan = plan_replicas(45.0, 3, 1.875, 0.05, turn, 1);
    ASSERT_TRUE(plan.has_value());
    expect_tiles(*plan, 45.0);
    for (std::size_t k = 1; k < plan->windows.size(); ++k) {
        const ReplicaWindow& w = plan->windows[k];
        EXPECT_GE(w.log_from_s, 0.05);
        EXPECT_LT(w.log_from_s, 0.05 + turn);
        const double turns = w.shift_s / turn;
        EXPECT_NEAR(turns, std::round(turns), 1e-9) << k;  // the part's angle the same in both clocks
        // Balanced to within a turn: every replica's own run ends near replica 0's remaining time.
        EXPECT_NEAR(w.run_to_s, plan->windows[0].run_to_s - 1.875, turn) << k;
    }
}

TEST(ReplicaPlan, NoPlanWhenThereIsNothingToShare) {
    EXPECT_FALSE(plan_replicas(1.0, 2, 0.6, 0.5, 0.0, 1).has_value());   // pilot + warm-up past the duration
    EXPECT_FALSE(plan_replicas(10.0, 1, 0.5, 0.1, 0.0, 1).has_value());  // one replica
    EXPECT_FALSE(plan_replicas(10.0, 2, 0.5, 0.0, 0.0, 1).has_value());  // no measured warm-up
}

// Until coverage: rounds of one slot a replica, laid end to end in replica order. K = 3, a pilot
// of 2 s holding 4000 impacts (2000 /s), a warm-up of 0.3 s, a turn of 1.5 s: a round is
// kRoundImpacts at that rate, rounded up to whole turns.
TEST(ReplicaPlan, RoundsTileTheRunKeepEachReplicasClockAndShiftByWholeTurns) {
    const double turn = 1.5;
    const auto plan = plan_rounds(3, 2.0, 0.3, 4000, turn, 7);
    ASSERT_TRUE(plan.has_value());
    const double wanted = static_cast<double>(kRoundImpacts) / 2000.0;
    EXPECT_DOUBLE_EQ(plan->round_s, std::ceil(wanted / turn) * turn);
    EXPECT_DOUBLE_EQ(plan->first_s, 2.0 + 0.3 + plan->round_s);
    EXPECT_EQ(plan->seeds[0], 7u);
    double run_s = 0.0;                  // where the next slot must begin
    std::vector<double> own_s(3, -1.0);  // each replica's own time its last slot ended
    for (int round = 0; round < 5; ++round)
        for (int k = 0; k < 3; ++k) {
            const ReplicaWindow w = plan->slot(round, k);
            EXPECT_EQ(w.replica, k);
            EXPECT_EQ(w.seed, replica_seed(7, k));
            EXPECT_NEAR(w.window_start_s(), run_s, 1e-12 * (1.0 + run_s)) << round << " " << k;
            // The slot's place, exactly where the last one ended.
            if (round > 0 || k > 0) {
                EXPECT_EQ(plan->slot_start_s(round, k), run_s) << round << " " << k;
            }
            EXPECT_NEAR(plan->slot_end_s(round, k), w.window_end_s(), 1e-12 * (1.0 + run_s)) << round << " " << k;
            if (round > 0 || k > 0) {
                EXPECT_NEAR(w.run_to_s - w.log_from_s, plan->round_s, 1e-12) << round << " " << k;
            }
            if (own_s[static_cast<std::size_t>(k)] >= 0.0) {  // on from where its last slot ended
                EXPECT_NEAR(w.log_from_s, own_s[static_cast<std::size_t>(k)], 1e-12 * (1.0 + run_s)) << round << " " << k;
            } else if (k > 0) {  // its first: past the warm-up
                EXPECT_GE(w.log_from_s, 0.3) << k;
            }
            const double turns = w.shift_s / turn;  // the part's angle kept
            EXPECT_NEAR(turns, std::round(turns), 1e-9) << round << " " << k;
            EXPECT_GE(w.shift_s, 0.0);
            own_s[static_cast<std::size_t>(k)] = w.run_to_s;
            run_s = plan->slot_end_s(round, k);
        }
    // Nothing turns: the round is the rate's; nothing to plan without replicas, warm-up or impacts.
    const auto still = plan_rounds(2, 1.0, 0.1, 1000, 0.0, 1);
    ASSERT_TRUE(still.has_value());
    EXPECT_DOUBLE_EQ(still->round_s, static_cast<double>(kRoundImpacts) / 1000.0);
    EXPECT_DOUBLE_EQ(still->first_from_s[1], 0.1);
    EXPECT_FALSE(plan_rounds(1, 1.0, 0.1, 1000, 0.0, 1).has_value());
    EXPECT_FALSE(plan_rounds(2, 1.0, 0.0, 1000, 0.0, 1).has_value());
    EXPECT_FALSE(plan_rounds(2, 1.0, 0.1, 0, 0.0, 1).has_value());
    // Its duration only caps a run until coverage: the pilot starts at 1 s at most.
    EXPECT_DOUBLE_EQ(first_round_pilot_s(4000.0, 2), 1.0);
    EXPECT_DOUBLE_EQ(first_round_pilot_s(64.0, 2), 1.0);
    EXPECT_DOUBLE_EQ(first_round_pilot_s(2.0, 2), 0.5);  // a cap too short for 1 s: its last pilot
}

TEST(ReplicaPlan, ThePilotDoublesFromAFractionOfTheShare) {
    EXPECT_DOUBLE_EQ(first_pilot_s(64.0, 2), 0.5);
    EXPECT_DOUBLE_EQ(last_pilot_s(64.0, 2), 16.0);
}

std::shared_ptr<const Model> model_of(const std::string& scene, std::vector<std::string> overrides = {}) {
    return compile_model(parse_scene(std::string(PEENSIM_SOURCE_DIR) + "/scenes/" + scene, std::nullopt, overrides));
}

TEST(ReplicaPlan, ScenesThatAreNotSteadyAreRefusedWithTheReason) {
    EXPECT_FALSE(replica_refusal(*model_of("gear.yaml")).has_value());
    EXPECT_FALSE(replica_refusal(*model_of("rotating-gear.yaml")).has_value());
    EXPECT_DOUBLE_EQ(turn_period_s(*model_of("rotating-gear.yaml")), 2.0);
    EXPECT_EQ(turn_period_s(*model_of("gear.yaml")), 0.0);
    const auto sources = replica_refusal(*model_of("nozzle-gear.yaml"));
    ASSERT_TRUE(sources.has_value());
    EXPECT_NE(sources->find("shot sources"), std::string::npos) << *sources;
    const auto history = replica_refusal(*model_of(
        "gear.yaml",
        {"contacts.shot-TA6V={law: impact-history, restitution_by_hits: [0.4, 0.5, 0.56], influence_distance: 0.58 mm, f: 0.3}"}));
    ASSERT_TRUE(history.has_value());
    EXPECT_NE(history->find("impact history"), std::string::npos) << *history;
    // A run until coverage is steady too: its replicas run in rounds (replica_rounds.h).
    EXPECT_FALSE(replica_refusal(*model_of("gear.yaml", {"process.until_coverage=98%"})).has_value());
}

}  // namespace
}  // namespace peensim
