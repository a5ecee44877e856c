// An exact, event-driven reference for one shot bouncing along z between a sinusoidally vibrating
// floor (the sonotrode) and a static ceiling. It exists to test the engine's sonotrode treatment:
// no time step, free flight is the exact parabola, and every contact time is a root of a smooth
// function found to ~1e-15 s, so its impact rates and speeds are the truth the engine's must approach.
//
// Physics (shot-peening-model.md, eq. 2, 4, 5 reduced to 1D):
//   floor surface   z_f(t) = A sin(2 pi F t + phase),  velocity V_f(t) = 2 pi F A cos(2 pi F t + phase)
//   ceiling         the static plane z = H
//   floor impact    u = v - V_f(t*) < 0  ->  v' = V_f(t*) - C_floor(|u|) u
//   ceiling impact  v > 0                ->  v' = -C_ceiling(v) v
//   restitution     C(V) = C0 if V < V0, else C0 (V / V0)^(-1/4)
// The shot's centre z stays in [z_f(t) + R, H - R].
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace peensim::testing {

struct VibratingFloorEvent;

struct VibratingFloorCase {
    double R;           // shot radius (m)
    double g;           // gravity magnitude (m/s^2), >= 0, acting towards -z
    double A;           // floor vibration amplitude (m), >= 0
    double F;           // floor vibration frequency (Hz), > 0
    double phase;       // floor phase at t = 0 (rad)
    double H;           // height of the ceiling plane (m); needs H - 2R > A
    double z0;          // centre height at t = 0 (m)
    double v0;          // vertical velocity at t = 0 (m/s)
    double C0_floor;    // shot-floor restitution in the elastic regime (-)
    double V0_floor;    // shot-floor elastic/plastic threshold speed (m/s), > 0
    double C0_ceiling;  // shot-ceiling restitution in the elastic regime (-)
    double V0_ceiling;  // shot-ceiling elastic/plastic threshold speed (m/s), > 0
    double duration;    // simulated time (s)

    // Optional settings.
    double statistics_start = 0.0;  // s: impacts before this time are simulated but not counted
    // m/s: a floor rebound slower than this (relative to the floor) while the floor accelerates
    // upwards faster than -g starts a ride on the floor instead of an endless chatter (see .cpp).
    // Floor approaches slower than this are touches, not counted as impacts.
    double chatter_speed = 1e-6;
    // m: an initial floor (ceiling) overlap up to this is taken as contact, more is an error.
    double contact_tolerance = 1e-12;
    std::size_t max_recorded_events = 0;     // events kept in VibratingFloorStats::first_events
    std::uint64_t max_events = 100'000'000;  // cap on flights + rides; exceeding it throws
    // Called with every event of the whole run as it happens (impacts of any speed down to
    // chatter_speed, captures, releases), before and after statistics_start: lets a caller bin
    // impacts by time window or speed without keeping them all.
    std::function<void(const VibratingFloorEvent&)> on_event{};
};

enum class VibratingFloorEventKind {
    floor_impact,    // an impact on the floor (counted)
    ceiling_impact,  // an impact on the ceiling (counted)
    floor_capture,   // the shot starts riding on the floor (chatter rule)
    floor_release,   // the riding shot leaves the floor (floor acceleration fell to -g)
};

struct VibratingFloorEvent {
    double time;  // s
    VibratingFloorEventKind kind;
    double speed;     // m/s: normal impact speed (|u| on the floor, v on the ceiling); 0 otherwise
    double z;         // m: centre height after the event
    double v_before;  // m/s: velocity just before the event
    double v_after;   // m/s: velocity just after the event (the flight that follows starts here)
    double gap;       // m: floor (ceiling) gap of the free-flight parabola at the event, before the
                      // shot is placed exactly on the surface; negative means penetration
};

struct ImpactSpeedStats {
    std::uint64_t count = 0;
    double mean = 0.0;  // m/s, normal impact speed
    double rms = 0.0;   // m/s
};

struct VibratingFloorStats {
    ImpactSpeedStats floor;                         // counted impacts in [statistics_start, duration]
    ImpactSpeedStats ceiling;                       // counted impacts in [statistics_start, duration]
    double counted_time = 0.0;                      // s: duration - statistics_start
    std::uint64_t floor_captures = 0;               // rides started by the chatter rule (whole run)
    std::uint64_t events_total = 0;                 // all recorded-kind events of the whole run
    double final_z = 0.0;                           // m: centre height at t = duration
    double final_v = 0.0;                           // m/s: velocity at t = duration
    bool final_riding = false;                      // the shot rides on the floor at t = duration
    std::vector<VibratingFloorEvent> first_events;  // the first max_recorded_events events

    double floor_rate() const;    // counted floor impacts per second (1/s)
    double ceiling_rate() const;  // counted ceiling impacts per second (1/s)
};

// Runs the case from t = 0 to case.duration. Throws std::invalid_argument for an inconsistent case
// and std::runtime_error if case.max_events is exceeded.
VibratingFloorStats simulate_vibrating_floor(const VibratingFloorCase& c);

}  // namespace peensim::testing
