// Tests of the exact vibrating-floor reference (tests/support/vibrating_floor_reference.h) against
// closed forms, conservation and self-consistency, and the "typical USP" case the engine is later
// compared with.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstddef>
#include <iostream>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/vibrating_floor_reference.h"

namespace peensim::testing {
namespace {

using Kind = VibratingFloorEventKind;
constexpr double kPi = std::numbers::pi;

double relative_error(double value, double expected) { return std::abs(value - expected) / std::abs(expected); }

std::vector<VibratingFloorEvent> events_of_kind(const VibratingFloorStats& s, Kind kind) {
    std::vector<VibratingFloorEvent> out;
    for (const VibratingFloorEvent& e : s.first_events) {
        if (e.kind == kind) out.push_back(e);
    }
    return out;
}

// The typical USP case of the brief: 1 mm shot, 25 um at 20 kHz, ceiling at 20 mm, titanium floor
// (C0 0.9, V0 1.5 m/s), steel ceiling (C0 0.95, V0 2 m/s), shot at rest on the floor at t = 0.
VibratingFloorCase typical_usp_case(double duration) {
    return VibratingFloorCase{.R = 1e-3,
                              .g = 9.81,
                              .A = 25e-6,
                              .F = 20e3,
                              .phase = 0.0,
                              .H = 20e-3,
                              .z0 = 1e-3,
                              .v0 = 0.0,
                              .C0_floor = 0.9,
                              .V0_floor = 1.5,
                              .C0_ceiling = 0.95,
                              .V0_ceiling = 2.0,
                              .duration = duration};
}

TEST(VibratingFloorReference, StillFloorDropMatchesClosedForm) {
    // A drop from h0 onto a still floor with a constant restitution C (V0 far above every speed):
    // impact k (from 0) at speed C^k v1, v1 = sqrt(2 g h0), first at sqrt(2 h0 / g), then every
    // 2 C^k v1 / g; the apex after impact k is C^(2(k+1)) h0.
    const double R = 1e-3, g = 9.81, h0 = 0.1, C = 0.8;
    VibratingFloorCase c{.R = R,
                         .g = g,
                         .A = 0.0,
                         .F = 20e3,
                         .phase = 0.0,
                         .H = 10.0,
                         .z0 = R + h0,
                         .v0 = 0.0,
                         .C0_floor = C,
                         .V0_floor = 1e3,
                         .C0_ceiling = 0.9,
                         .V0_ceiling = 1e3,
                         .duration = 2.0};
    c.max_recorded_events = 200;
    const VibratingFloorStats s = simulate_vibrating_floor(c);

    const double v1 = std::sqrt(2.0 * g * h0);
    const std::vector<VibratingFloorEvent> impacts = events_of_kind(s, Kind::floor_impact);
    // Checked over 20 bounces (speeds down to 0.02 m/s): event times are absolute doubles, so each
    // flight's duration carries ~1e-16 s of rounding, i.e. ~1e-15 m/s of impact speed, which is
    // more than 1e-12 relative for slower bounces.
    ASSERT_GE(impacts.size(), 20u);
    double t_expected = std::sqrt(2.0 * h0 / g);
    for (std::size_t k = 0; k < 20; ++k) {
        const double speed = std::pow(C, static_cast<double>(k)) * v1;
        const double apex = std::pow(C, 2.0 * static_cast<double>(k + 1)) * h0;
        const VibratingFloorEvent& e = impacts[k];
        EXPECT_LT(relative_error(e.time, t_expected), 1e-12) << "impact " << k;
        EXPECT_LT(relative_error(e.speed, speed), 1e-12) << "impact " << k;
        EXPECT_LT(relative_error(e.v_after * e.v_after / (2.0 * g), apex), 1e-12) << "impact " << k;
        EXPECT_EQ(e.z, R);
        t_expected += 2.0 * C * speed / g;
    }

    // The bounces stop by the chatter rule once the rebound C^(k+1) v1 falls below chatter_speed:
    // impact k = n - 1 with n the first integer where C^n v1 < 1e-6 m/s (n = 64 here). Then the
    // shot rests on the floor until the end.
    int n = 1;
    while (std::pow(C, n) * v1 >= c.chatter_speed) ++n;
    EXPECT_EQ(n, 64);
    EXPECT_EQ(s.floor.count, static_cast<std::uint64_t>(n));
    EXPECT_EQ(s.ceiling.count, 0u);
    EXPECT_EQ(s.floor_captures, 1u);
    EXPECT_TRUE(s.final_riding);
    EXPECT_EQ(s.final_z, R);
    EXPECT_EQ(s.final_v, 0.0);
}

TEST(VibratingFloorReference, WeightlessShotShuttlesBetweenFloorAndCeiling) {
    // g = 0, still floor, C = 1: the shot shuttles at 1 m/s over the 9 mm between contacts. It
    // starts mid-way going up, so impact k is at 4.5 ms + k * 9 ms, on the ceiling for even k.
    // In 1 s: k = 0..110, i.e. 56 ceiling and 55 floor impacts.
    const double R = 1e-3;
    VibratingFloorCase c{.R = R,
                         .g = 0.0,
                         .A = 0.0,
                         .F = 1.0,
                         .phase = 0.0,
                         .H = 11e-3,
                         .z0 = R + 4.5e-3,
                         .v0 = 1.0,
                         .C0_floor = 1.0,
                         .V0_floor = 10.0,
                         .C0_ceiling = 1.0,
                         .V0_ceiling = 10.0,
                         .duration = 1.0};
    c.max_recorded_events = 200;
    const VibratingFloorStats s = simulate_vibrating_floor(c);

    EXPECT_EQ(s.ceiling.count, 56u);
    EXPECT_EQ(s.floor.count, 55u);
    EXPECT_DOUBLE_EQ(s.floor.mean, 1.0);
    EXPECT_DOUBLE_EQ(s.ceiling.rms, 1.0);
    ASSERT_EQ(s.first_events.size(), 111u);
    for (std::size_t k = 0; k < s.first_events.size(); ++k) {
        const VibratingFloorEvent& e = s.first_events[k];
        EXPECT_EQ(e.kind, k % 2 == 0 ? Kind::ceiling_impact : Kind::floor_impact) << k;
        EXPECT_LT(relative_error(e.time, 4.5e-3 + 9e-3 * static_cast<double>(k)), 1e-12) << k;
    }
    EXPECT_LT(std::abs(s.final_z - (R + 3.5e-3)), 1e-12);  // 5.5 ms after the last ceiling impact
}

TEST(VibratingFloorReference, ElasticVibratingFloorPumpsEnergyWithoutPenetration) {
    // With C = 1 on both surfaces nothing dissipates and the vibrating floor pumps energy in
    // (Fermi acceleration): impact speeds climb far above the floor's peak speed A w.
    VibratingFloorCase c = typical_usp_case(1.0);
    c.C0_floor = 1.0;
    c.C0_ceiling = 1.0;
    c.V0_floor = 1e6;
    c.V0_ceiling = 1e6;
    c.max_recorded_events = 100'000;
    const VibratingFloorStats s = simulate_vibrating_floor(c);
    ASSERT_EQ(s.first_events.size(), s.events_total);  // every event is checked below

    const double w = 2.0 * kPi * c.F;  // rad/s
    const double floor_peak_speed = c.A * w;
    std::cout << "[ elastic  ] floor impacts " << s.floor.count << ", mean speed " << s.floor.mean << " m/s (floor peak "
              << floor_peak_speed << " m/s)\n";
    EXPECT_GT(s.floor.count, 1000u);
    EXPECT_GT(s.floor.mean, 5.0 * floor_peak_speed);
    EXPECT_GT(s.ceiling.mean, 5.0 * floor_peak_speed);

    const auto floor_z = [&](double t) { return c.A * std::sin(w * t + c.phase); };
    const auto floor_v = [&](double t) { return c.A * w * std::cos(w * t + c.phase); };
    const double gap_floor = -1e-12;  // m, penetration allowed by rounding
    for (std::size_t k = 0; k < s.first_events.size(); ++k) {
        const VibratingFloorEvent& e = s.first_events[k];
        if (e.kind == Kind::floor_impact) {
            EXPECT_GE(e.gap, gap_floor) << "event " << k;
            // Elastic in the floor's frame: the relative speed reverses exactly (up to the
            // ~1e-10 m/s rounding of w t in this independent floor velocity).
            EXPECT_NEAR((e.v_after - floor_v(e.time)) + (e.v_before - floor_v(e.time)), 0.0, 1e-9);
        } else if (e.kind == Kind::ceiling_impact) {
            EXPECT_GE(e.gap, gap_floor) << "event " << k;
            EXPECT_EQ(e.v_after, -e.v_before);
        }
        if (e.kind == Kind::floor_capture || k + 1 == s.first_events.size()) continue;
        // Sample the flight to the next event densely (128 samples per floor period): the shot
        // must never be inside the floor or the ceiling, so no contact was skipped.
        const double t_next = s.first_events[k + 1].time;
        const double dt = t_next - e.time;
        const int samples = std::max(64, static_cast<int>(dt * c.F * 128.0));
        for (int i = 1; i < samples; ++i) {
            const double s_flight = dt * i / samples;
            const double t = e.time + s_flight;
            const double z = e.z + e.v_after * s_flight - 0.5 * c.g * s_flight * s_flight;
            ASSERT_GE(z - c.R - floor_z(t), gap_floor) << "flight after event " << k;
            ASSERT_LE(z + c.R - c.H, -gap_floor) << "flight after event " << k;
        }
    }
}

TEST(VibratingFloorReference, RidingShotLeavesWhenTheFloorDeceleratesFasterThanGravity) {
    // A shot moving with the floor at the floor's mid-stroke going down (phase pi, acceleration 0,
    // more than -g) sticks to it, and leaves where the floor acceleration -A w^2 sin(theta) falls
    // to -g: theta = 2 pi + asin(g / (A w^2)), with the floor's velocity A w cos(theta).
    VibratingFloorCase c = typical_usp_case(0.01);
    c.phase = kPi;
    const double w = 2.0 * kPi * c.F;  // rad/s
    c.z0 = c.R + c.A * std::sin(c.phase);
    c.v0 = c.A * w * std::cos(c.phase);
    c.max_recorded_events = 4;
    const VibratingFloorStats s = simulate_vibrating_floor(c);

    ASSERT_GE(s.first_events.size(), 3u);
    EXPECT_EQ(s.first_events[0].kind, Kind::floor_capture);
    EXPECT_EQ(s.first_events[0].time, 0.0);
    const double sin_release = c.g / (c.A * w * w);
    const double theta_release = 2.0 * kPi + std::asin(sin_release);
    const VibratingFloorEvent& release = s.first_events[1];
    EXPECT_EQ(release.kind, Kind::floor_release);
    EXPECT_LT(relative_error(release.time, (theta_release - c.phase) / w), 1e-12);
    EXPECT_LT(relative_error(release.v_after, c.A * w * std::sqrt(1.0 - sin_release * sin_release)), 1e-12);
    EXPECT_EQ(s.first_events[2].kind, Kind::ceiling_impact);  // 3.14 m/s reaches the ceiling
}

TEST(VibratingFloorReference, WeakVibrationLetsTheShotSettle) {
    // A w^2 = 0.39 m/s^2 < g: the floor never pulls away from a resting shot, so a dropped shot
    // ends riding on it for good.
    VibratingFloorCase c = typical_usp_case(5.0);
    c.A = 1e-6;
    c.F = 100.0;
    c.z0 = c.R + 5e-3;
    const VibratingFloorStats s = simulate_vibrating_floor(c);
    EXPECT_TRUE(s.final_riding);
    EXPECT_EQ(s.floor_captures, 1u);
    EXPECT_GT(s.floor.count, 10u);
    EXPECT_EQ(s.ceiling.count, 0u);
    const double w = 2.0 * kPi * c.F;
    EXPECT_NEAR(s.final_z, c.R + c.A * std::sin(w * c.duration), 1e-15);
}

TEST(VibratingFloorReference, RejectsInconsistentCasesAndRunaways) {
    VibratingFloorCase below = typical_usp_case(1.0);
    below.z0 = below.R - 1e-9;
    EXPECT_THROW(simulate_vibrating_floor(below), std::invalid_argument);
    VibratingFloorCase no_room = typical_usp_case(1.0);
    no_room.H = 2.0 * no_room.R + no_room.A;
    EXPECT_THROW(simulate_vibrating_floor(no_room), std::invalid_argument);
    VibratingFloorCase capped = typical_usp_case(1.0);
    capped.max_events = 10;
    EXPECT_THROW(simulate_vibrating_floor(capped), std::runtime_error);
}

TEST(VibratingFloorReference, TypicalUspCaseHasStableRates) {
    const auto clock_start = std::chrono::steady_clock::now();
    const VibratingFloorStats s = simulate_vibrating_floor(typical_usp_case(10.0));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
    std::cout << "[ USP 10 s ] floor " << s.floor_rate() << " /s, mean " << s.floor.mean << " m/s, rms " << s.floor.rms << " m/s; ceiling "
              << s.ceiling_rate() << " /s, mean " << s.ceiling.mean << " m/s, rms " << s.ceiling.rms << " m/s; captures "
              << s.floor_captures << "; " << seconds << " s wall\n";
    RecordProperty("usp_floor_rate_per_s", std::to_string(s.floor_rate()));
    RecordProperty("usp_floor_mean_speed_m_per_s", std::to_string(s.floor.mean));
    RecordProperty("usp_ceiling_rate_per_s", std::to_string(s.ceiling_rate()));
    RecordProperty("usp_ceiling_mean_speed_m_per_s", std::to_string(s.ceiling.mean));
    for (const double x : {s.floor_rate(), s.ceiling_rate(), s.floor.mean, s.ceiling.mean, s.floor.rms, s.ceiling.rms}) {
        EXPECT_TRUE(std::isfinite(x));
        EXPECT_GT(x, 0.0);
    }
    EXPECT_LT(seconds, 1.0);  // ~5 ms in a release build

    // One shot's impact statistics wander by up to ~15 % between 5 s windows (the shot's energy
    // has a long memory), so stability is checked on two 200 s halves, which agree to ~2 %.
    const double half = 200.0;  // s
    const VibratingFloorStats first = simulate_vibrating_floor(typical_usp_case(half));
    VibratingFloorCase second_case = typical_usp_case(2.0 * half);
    second_case.statistics_start = half;
    const VibratingFloorStats second = simulate_vibrating_floor(second_case);
    std::cout << "[ USP 2x" << half << " s ] floor " << first.floor_rate() << " | " << second.floor_rate() << " /s, mean "
              << first.floor.mean << " | " << second.floor.mean << " m/s; ceiling " << first.ceiling_rate() << " | "
              << second.ceiling_rate() << " /s, mean " << first.ceiling.mean << " | " << second.ceiling.mean << " m/s\n";
    const double tolerance = 0.04;
    EXPECT_LT(relative_error(second.floor_rate(), first.floor_rate()), tolerance);
    EXPECT_LT(relative_error(second.ceiling_rate(), first.ceiling_rate()), tolerance);
    EXPECT_LT(relative_error(second.floor.mean, first.floor.mean), tolerance);
    EXPECT_LT(relative_error(second.ceiling.mean, first.ceiling.mean), tolerance);
    EXPECT_LT(relative_error(second.floor.rms, first.floor.rms), tolerance);
    EXPECT_LT(relative_error(second.ceiling.rms, first.ceiling.rms), tolerance);
    // The 10 s statistics lie within ~15 % of the long-run values.
    EXPECT_LT(relative_error(s.floor_rate(), second.floor_rate()), 0.15);
    EXPECT_LT(relative_error(s.floor.mean, second.floor.mean), 0.15);
}

}  // namespace
}  // namespace peensim::testing
