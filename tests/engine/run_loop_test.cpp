// The one run loop (engine/run_loop.h): listeners see every logged impact once, in order, with the
// state at each step's end; restart points; a stop lands on a restart point; a pause request is
// honoured by the event-driven scheme; the start, finish and interrupt hooks come once each, first
// and last.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/run_loop.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

TestSceneSpec small(const std::string& scheme) {
    TestSceneSpec spec = thrown_shot_scene(16, 0.05);
    spec.scheme = scheme;
    spec.log = {"sonotrode", "chamber"};
    if (scheme == "soft") spec.soft = SoftSpec{};  // the soft scheme needs soft-sphere laws
    return spec;
}

struct Recorder final : RunListener {
    std::vector<ImpactRecord> impacts;
    std::vector<double> step_ends_s, restart_times_s;
    double pause_s = std::numeric_limits<double>::infinity();
    bool paused_exactly = false;
    double pause_at_s() const override { return pause_s; }
    void after_step(const Simulation& sim, const std::vector<ImpactRecord>& step) override {
        impacts.insert(impacts.end(), step.begin(), step.end());
        step_ends_s.push_back(sim.state().time.seconds());
        if (sim.state().time.seconds() == pause_s) paused_exactly = true;
    }
    void at_restart_point(const Simulation& sim) override { restart_times_s.push_back(sim.state().time.seconds()); }
    // The hooks, in the order heard ("step" for every after_step), with the time each saw.
    std::vector<std::string> calls;
    std::vector<double> call_times_s;
    void heard(const char* what, const Simulation& sim) {
        if (!calls.empty() && calls.back() == "step" && std::string(what) == "step") return;  // a run of steps: one entry
        calls.push_back(what);
        call_times_s.push_back(sim.state().time.seconds());
    }
    void at_start(const Simulation& sim) override { heard("start", sim); }
    void at_finish(const Simulation& sim) override { heard("finish", sim); }
    void at_interrupt(const Simulation& sim) override { heard("interrupt", sim); }
};

// after_step also records "step" (kept apart from the impact tally above).
struct HookRecorder final : RunListener {
    Recorder r;
    void after_step(const Simulation& sim, const std::vector<ImpactRecord>& step) override {
        r.after_step(sim, step);
        r.heard("step", sim);
    }
    void at_start(const Simulation& sim) override { r.at_start(sim); }
    void at_finish(const Simulation& sim) override { r.at_finish(sim); }
    void at_interrupt(const Simulation& sim) override { r.at_interrupt(sim); }
};

class RunLoopSchemes : public ::testing::TestWithParam<std::string> {};

TEST_P(RunLoopSchemes, ListenersSeeWhatStepByStepDrivingSees) {
    const TestScene scene(small(GetParam()));
    // By hand: the reference the loop is compared with.
    Simulation by_hand(scene.compile());
    std::vector<ImpactRecord> expected, step;
    while (!by_hand.finished()) {
        by_hand.step(step);
        expected.insert(expected.end(), step.begin(), step.end());
        step.clear();
    }
    // Through the loop, two listeners.
    Simulation sim(scene.compile());
    Recorder a, b;
    RunLoop loop(sim);
    loop.add(a);
    loop.add(b);
    EXPECT_TRUE(loop.run());
    EXPECT_TRUE(sim.finished());
    ASSERT_FALSE(expected.empty());
    ASSERT_EQ(a.impacts.size(), expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
        EXPECT_EQ(a.impacts[k].time_s, expected[k].time_s) << k;
        EXPECT_EQ(a.impacts[k].shot, expected[k].shot) << k;
    }
    EXPECT_EQ(b.impacts.size(), a.impacts.size());
    EXPECT_TRUE(std::is_sorted(a.step_ends_s.begin(), a.step_ends_s.end()));
    // Time stepping is at a restart point after every step; the event-driven scheme after a budget
    // of work (~0.2 s of wall time), which this short scene does not reach.
    if (GetParam() == "step") {
        EXPECT_EQ(a.restart_times_s.size(), a.step_ends_s.size());
    }
}

TEST_P(RunLoopSchemes, AStopEndsTheRunAtTheNextRestartPoint) {
    const TestScene scene(small(GetParam()));
    Simulation sim(scene.compile());
    Recorder r;
    RunLoop loop(sim);
    loop.add(r);
    const bool finished = loop.run([](std::uint64_t steps) { return steps >= 20; });
    if (GetParam() == "step") {
        EXPECT_FALSE(finished);
        EXPECT_EQ(r.step_ends_s.size(), 20u);  // every step is a restart point
    } else {
        EXPECT_TRUE(finished);  // no restart point in this short scene: it runs to its end
        EXPECT_TRUE(r.restart_times_s.empty());
    }
    EXPECT_EQ(sim.finished(), finished);
    if (!finished) {
        EXPECT_TRUE(sim.at_restart_point()) << "stopped between restart points";
    }
}

TEST_P(RunLoopSchemes, APauseIsHonouredOnceAndThenNoLongerHolds) {
    const TestScene scene(small(GetParam()));
    Simulation sim(scene.compile());
    Recorder r;
    r.pause_s = 0.0123;  // s; still asked for after it has passed: ignored, the run goes on
    RunLoop loop(sim);
    loop.add(r);
    EXPECT_TRUE(loop.run());
    EXPECT_TRUE(sim.finished());
    if (GetParam() == "event") {
        EXPECT_TRUE(r.paused_exactly) << "the event-driven scheme stops exactly at a pause";
    }
}

TEST_P(RunLoopSchemes, StartComesFirstAndFinishLastOnceEach) {
    const TestScene scene(small(GetParam()));
    Simulation sim(scene.compile());
    const double t0_s = sim.state().time.seconds();
    HookRecorder h;
    RunLoop loop(sim);
    loop.add(h);
    ASSERT_TRUE(loop.run());
    const std::vector<std::string> expected{"start", "step", "finish"};
    EXPECT_EQ(h.r.calls, expected);
    ASSERT_EQ(h.r.call_times_s.size(), 3u);
    EXPECT_EQ(h.r.call_times_s.front(), t0_s);                       // before any step
    EXPECT_EQ(h.r.call_times_s.back(), sim.state().time.seconds());  // the run's end
    EXPECT_TRUE(sim.finished());
}

TEST_P(RunLoopSchemes, AStoppedRunEndsWithInterruptNotFinish) {
    // Stopped after the first step: the run ends at the next restart point, which is then the state
    // the interrupt hook sees (time stepping: that step; the event-driven schemes: a restart point
    // once their work budget or restart interval is reached, here the scene's end first).
    const TestScene scene(small(GetParam()));
    Simulation sim(scene.compile());
    HookRecorder h;
    RunLoop loop(sim);
    loop.add(h);
    const bool finished = loop.run([](std::uint64_t) { return true; });
    ASSERT_EQ(h.r.calls.size(), 3u);
    EXPECT_EQ(h.r.calls[0], "start");
    EXPECT_EQ(h.r.calls[1], "step");
    EXPECT_EQ(h.r.calls[2], finished ? "finish" : "interrupt");
    if (GetParam() == "step") {
        EXPECT_FALSE(finished);
        EXPECT_EQ(h.r.step_ends_s.size(), 1u);
    }
    if (!finished) {
        EXPECT_TRUE(sim.at_restart_point());
        EXPECT_EQ(h.r.call_times_s.back(), sim.state().time.seconds());
    }
}

INSTANTIATE_TEST_SUITE_P(Schemes, RunLoopSchemes, ::testing::Values(std::string("step"), std::string("event"), std::string("soft")),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace peensim::testing
