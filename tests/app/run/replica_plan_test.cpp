// The replicas' windows (app/run/replica_plan.h): they tile the run's time exactly, each replica
// warms up at least the measured transient, a rotating part's windows are shifted by whole turns,
// and all replicas end together (equal speed); scenes that are not steady are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "app/run/replica_plan.h"
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
    const auto until = replica_refusal(*model_of("gear.yaml", {"process.until_coverage=98%"}));
    ASSERT_TRUE(until.has_value());
    EXPECT_NE(until->find("until_coverage"), std::string::npos) << *until;
}

}  // namespace
}  // namespace peensim
