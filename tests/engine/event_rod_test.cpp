// The rod scene (scenes/rod.yaml) with the coefficients of the event-driven prototype of the
// reference notes (C = 0.9 at every speed, mu = 1; support/rod_prototype.h), run with the
// event-driven scheme (its figures against the prototype's: rod_prototype_test.cpp, both schemes):
//  - its rod impact rate and mean normal impact speed must equal, within statistical noise, those of
//    time stepping whose steps are at most 1/20 of the sonotrode period (the only time stepping the
//    notes found to resolve the plate), run on from the event run's own state after 0.1 s of
//    settling (the bed fluidising from rest), so both measure the same steady state and the costly
//    fine stepping pays for no settling (event: 1.0 s measured, ~2 s of wall time; fine stepping:
//    0.5 s measured, ~17 s of wall time on this machine).
//
// Noise: batch means. The measured window is cut into batches of kBatch; the standard error of a
// scheme's figure is the spread of its batch values over sqrt(batches). The difference of the two
// schemes' means must stay within 3 combined standard errors (as the vibrating-floor test). A 3 s
// run of R/4 time stepping (60 batches of 50 ms) gave batch spreads of 4.8 % for the rate and 3.5 %
// for the mean speed, lag-1 autocorrelations of the batch values within +-0.07, and the same
// standard error of the whole run's mean from batches of 25, 50, 100 or 200 ms (0.61-0.68 % for the
// rate): 50 ms batches are independent. With 20 and 10 batches the bound is then ~5.6 % for the
// rate and ~4.1 % for the speed; the measured bounds are printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "engine/simulation.h"
#include "engine/time_stepping.h"
#include "model/model.h"
#include "scene/scene_parser.h"
#include "support/rod_prototype.h"
#include "support/run_report.h"
#include "support/run_through_loop.h"

namespace peensim::testing {
namespace {

constexpr double kSettle = 0.1;    // s, left out: the bed fluidising from rest
constexpr double kEventEnd = 1.1;  // s, event run (1.0 s measured)
constexpr double kFineEnd = 0.6;   // s, fine time stepping from the settled state (0.5 s measured)
constexpr double kBatch = 0.05;    // s, batch length of the batch means
// -, travel per step over R of the fine time stepping: with the plate's peak speed (3.14 m/s) as the
// least v_max of eq. 7, steps are at most 2.39 us, under 1/20 of the 50 us period (asserted below).
constexpr double kFineTravelFraction = 0.0075;

std::shared_ptr<const Model> rod_model(const std::vector<std::string>& extra) {
    std::vector<std::string> overrides = kPrototypeCoefficients;
    overrides.insert(overrides.end(), extra.begin(), extra.end());
    return compile_model(parse_scene_file(std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml", overrides));
}

// Rod impacts per batch of kBatch from kSettle on.
struct Batches {
    std::vector<double> count;      // rod impacts
    std::vector<double> speed_sum;  // m/s, summed normal impact speeds
    explicit Batches(double end)
        : count(static_cast<std::size_t>(std::llround((end - kSettle) / kBatch)), 0.0), speed_sum(count.size(), 0.0) {}
    void add(const std::vector<ImpactRecord>& impacts) {
        for (const ImpactRecord& r : impacts) {
            if (r.time_s < kSettle) continue;
            const auto b = std::min(count.size() - 1, static_cast<std::size_t>((r.time_s - kSettle) / kBatch));
            count[b] += 1.0;
            speed_sum[b] += r.vn_in_m_per_s;
        }
    }
};

struct Estimate {
    double mean = 0.0;
    double standard_error = 0.0;
};

Estimate batch_estimate(const std::vector<double>& values) {
    const double n = static_cast<double>(values.size());
    double sum = 0.0, sum2 = 0.0;
    for (double v : values) sum += v;
    const double mean = sum / n;
    for (double v : values) sum2 += (v - mean) * (v - mean);
    return {mean, std::sqrt(sum2 / (n - 1.0) / n)};
}

// Overall rate (1/s) and mean speed (m/s), with batch-mean standard errors.
struct RodFigures {
    Estimate rate, speed;
    double impacts = 0.0;
};

RodFigures figures(const Batches& b) {
    RodFigures f;
    std::vector<double> rates, speeds;
    double speed_sum = 0.0;
    for (std::size_t k = 0; k < b.count.size(); ++k) {
        rates.push_back(b.count[k] / kBatch);
        speeds.push_back(b.speed_sum[k] / std::max(1.0, b.count[k]));
        f.impacts += b.count[k];
        speed_sum += b.speed_sum[k];
    }
    f.rate = batch_estimate(rates);
    f.speed = batch_estimate(speeds);
    // The overall mean speed weighs every impact alike; its error is the batch spread's.
    f.speed.mean = speed_sum / std::max(1.0, f.impacts);
    return f;
}

// The batch series, for the report: "rate/speed" per batch.
std::string batch_series(const Batches& b) {
    std::string out;
    for (std::size_t k = 0; k < b.count.size(); ++k) {
        char cell[64];
        std::snprintf(cell, sizeof cell, " %.0f/%.3f", b.count[k] / kBatch, b.speed_sum[k] / std::max(1.0, b.count[k]));
        out += cell;
    }
    return out;
}

TEST(EngineEventRod, EventSchemeMatchesPeriodResolvingTimeStepping) {
    // Event run: settle to exactly kSettle (a pause), keep that state, run on to kEventEnd.
    const auto event_model = rod_model({"accuracy.scheme=event", "process.duration=" + std::to_string(kEventEnd) + " s"});
    ASSERT_EQ(event_model->description.accuracy.scheme, SteppingScheme::event);
    const auto t_event = std::chrono::steady_clock::now();
    Simulation event(event_model);
    Batches event_batches(kEventEnd);
    std::optional<SimulationState> settled;  // the state at the pause at kSettle
    run_through_loop(event, {.after_step =
                                 [&](const Simulation&, const std::vector<ImpactRecord>& impacts) {
                                     if (settled) {
                                         event_batches.add(impacts);
                                     } else if (event.state().time.seconds() >= kSettle) {
                                         settled = event.state();
                                     }
                                 },
                             .pause_at_s = [&](const Simulation&) { return settled ? std::numeric_limits<double>::infinity() : kSettle; }});
    ASSERT_TRUE(settled);
    ASSERT_EQ(settled->time.seconds(), kSettle);  // the event scheme stops exactly at a pause
    const double event_wall = seconds_since(t_event);
    EXPECT_EQ(event.state().health.serious(), 0u) << health_text(event.state().health);

    // Fine time stepping from the settled state.
    const auto fine_model = rod_model({"accuracy.scheme=step", "accuracy.travel_fraction=" + std::to_string(kFineTravelFraction),
                                       "process.duration=" + std::to_string(kFineEnd) + " s"});
    const double period = 1.0 / fine_model->sonotrode_component().kinematics.frequency_hz;
    const double g = fine_model->gravity_m_per_s2.norm();
    // v_max of eq. 7 is never below the plate's peak speed, so no step is longer than this:
    const double dt_bound =
        TimeStepping::step_for(fine_model->peak_surface_speed_m_per_s, g, kFineTravelFraction * fine_model->max_shot_radius_m);
    ASSERT_LE(dt_bound, period / 20.0);
    const auto t_fine = std::chrono::steady_clock::now();
    Simulation fine(fine_model, *settled);
    Batches fine_batches(kFineEnd);
    double longest_step = 0.0;
    double step_start = fine.state().time.seconds();  // s
    run_through_loop(fine, {.after_step = [&](const Simulation&, const std::vector<ImpactRecord>& impacts) {
                         longest_step = std::max(longest_step, fine.state().time.seconds() - step_start);
                         step_start = fine.state().time.seconds();
                         fine_batches.add(impacts);
                     }});
    const double fine_wall = seconds_since(t_fine);
    EXPECT_EQ(fine.state().health.serious(), 0u) << health_text(fine.state().health);
    EXPECT_LE(longest_step, period / 20.0 * (1.0 + 1e-9));

    const RodFigures e = figures(event_batches), f = figures(fine_batches);
    std::cout << "[ event rod] event scheme " << kSettle << "-" << kEventEnd << " s (" << event_wall << " s wall incl. settling, "
              << event.state().steps << " units of work): " << e.impacts << " rod impacts, rate " << e.rate.mean << " +- "
              << e.rate.standard_error << " /s, mean normal speed " << e.speed.mean << " +- " << e.speed.standard_error << " m/s\n";
    std::cout << "[ event rod] fine time stepping " << kSettle << "-" << kFineEnd << " s (" << fine_wall << " s wall, "
              << fine.state().steps - settled->steps << " steps, longest " << longest_step << " s, bound " << dt_bound << " s, period/20 "
              << period / 20.0 << " s): " << f.impacts << " rod impacts, rate " << f.rate.mean << " +- " << f.rate.standard_error
              << " /s, mean normal speed " << f.speed.mean << " +- " << f.speed.standard_error << " m/s\n";
    std::cout << "[ event rod] batches of " << kBatch << " s (rate /s / mean speed m/s): event" << batch_series(event_batches)
              << "\n[ event rod] fine time stepping" << batch_series(fine_batches) << "\n";
    const double rate_bound = 3.0 * std::hypot(e.rate.standard_error, f.rate.standard_error);
    const double speed_bound = 3.0 * std::hypot(e.speed.standard_error, f.speed.standard_error);
    std::cout << "[ event rod] difference event - fine: rate " << (e.rate.mean - f.rate.mean) / f.rate.mean * 100.0 << " % (bound 3 SE "
              << rate_bound / f.rate.mean * 100.0 << " %), speed " << (e.speed.mean - f.speed.mean) / f.speed.mean * 100.0
              << " % (bound 3 SE " << speed_bound / f.speed.mean * 100.0 << " %)\n";
    EXPECT_LE(std::abs(e.rate.mean - f.rate.mean), rate_bound);
    EXPECT_LE(std::abs(e.speed.mean - f.speed.mean), speed_bound);
}

}  // namespace
}  // namespace peensim::testing
