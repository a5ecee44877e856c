// Event-driven solution of the vibrating-floor case (see the header for the physics).
//
// Between events the shot flies on an exact parabola anchored at the last event (absolute time t0,
// height, velocity). Inside, heights are of the shot's lowest point, y = z - R (m), so the floor gap
// is G(t) = y(t) - z_f(t) and the ceiling sits at y_top = H - 2R.
//
// Finding the FIRST floor contact of a flight (first_floor_contact):
//  1. G > 0 wherever y > A (the floor never rises above A), so only the spans where the parabola is
//     at or below A are searched; their ends are exact quadratic roots. Once y reaches -A the gap is
//     surely <= 0, which bounds the search.
//  2. A span is cut at the zeros of G'' = -g + A w^2 sin(w t + phase) (two per period), so that G is
//     convex or concave on each piece. On a piece starting with G > 0: if G <= 0 at its end it
//     crossed exactly once (both shapes); if G > 0 at its end, a concave piece stayed positive and a
//     convex one can only have dipped below zero around its minimum, which is located (G' = 0) and
//     checked, so grazing contacts are not missed.
//  3. The crossing is located by safeguarded Newton/bisection to ~1e-15 s.
#include "support/vibrating_floor_reference.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace peensim::testing {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTwoPi = 2.0 * std::numbers::pi;
// s: contact times are resolved to this, or to 2 ulps of the time when that is coarser.
constexpr double kTimeTolerance = 1e-15;
// Newton/bisection steps per crossing; bisection alone needs ~50 from a full second to 1e-15 s.
constexpr int kMaxRootIterations = 300;
// Pieces walked in one contact search: a contact always happens within about one floor period
// once the shot is in the band, so this only guards against a programming error.
constexpr long kMaxPiecesPerSearch = 10'000'000;

double restitution(double C0, double V0, double speed) { return speed < V0 ? C0 : C0 * std::pow(speed / V0, -0.25); }

// The floor's motion in closed form, with the phase taken from fmod(t, T), which is exact: w * t
// in double would carry ~1e-10 rad of rounding at t ~ 10 s (3e-15 m of floor position at 25 um),
// more than the tiny gaps of a shot chattering on the floor.
class FloorMotion {
public:
    FloorMotion(double A, double F, double phase, double g) : A_(A), period_(1.0 / F), omega_(kTwoPi / period_), phase_(phase) {
        // The floor acceleration -A w^2 sin(theta) equals -g where sin(theta) = g / (A w^2).
        const double s = A > 0.0 ? g / (A * omega_ * omega_) : kInf;
        if (s < 1.0) {
            has_knots_ = true;
            release_fraction_ = cycle_fraction_of(std::asin(s));  // sin(theta) rising through s
            other_fraction_ = cycle_fraction_of(std::numbers::pi - std::asin(s));
        }
    }

    double amplitude() const { return A_; }  // m
    double angle(double t) const { return kTwoPi * (std::fmod(t, period_) / period_) + phase_; }
    double position(double t) const { return A_ * std::sin(angle(t)); }           // m
    double velocity(double t) const { return A_ * omega_ * std::cos(angle(t)); }  // m/s
    double acceleration(double t) const {                                         // m/s^2
        return -A_ * omega_ * omega_ * std::sin(angle(t));
    }

    // First time after t (s) where the floor acceleration equals -g (a zero of G''); +inf if none.
    double next_knot(double t) const {
        if (!has_knots_) return kInf;
        return std::min(next_time_at(release_fraction_, t), next_time_at(other_fraction_, t));
    }
    // First time after t (s) where the floor acceleration falls through -g; +inf if it never does.
    double next_release(double t) const { return has_knots_ ? next_time_at(release_fraction_, t) : kInf; }

private:
    double cycle_fraction_of(double theta) const {
        const double f = (theta - phase_) / kTwoPi;
        return f - std::floor(f);
    }
    double next_time_at(double fraction, double t) const {
        const double n0 = std::floor(t / period_);
        for (double n = n0 - 1.0; n <= n0 + 2.0; n += 1.0) {
            const double tk = (n + fraction) * period_;
            if (tk > t) return tk;
        }
        return kInf;  // not reached: (n0 + 2 + fraction) * period > t
    }

    double A_;       // m
    double period_;  // s
    double omega_;   // rad/s, 2 pi / period (consistent with the fmod phase)
    double phase_;   // rad
    bool has_knots_ = false;
    double release_fraction_ = 0.0;  // cycle fraction where sin(theta) = g / (A w^2), rising
    double other_fraction_ = 0.0;    // cycle fraction where sin(theta) = g / (A w^2), falling
};

// Free flight anchored at an event: exact, no accumulated error within a flight.
struct Flight {
    double t0;  // s
    double y0;  // m, lowest point of the shot at t0
    double v0;  // m/s at t0
    double g;   // m/s^2

    double height(double t) const {
        const double s = t - t0;
        return y0 + s * (v0 - 0.5 * g * s);
    }
    double velocity(double t) const { return v0 - g * (t - t0); }
};

// Times after the flight start (s) at which the parabola crosses a level upwards and downwards;
// +inf where it does not. Roots in the cancellation-free forms.
struct Crossings {
    double up = kInf;
    double down = kInf;
};

Crossings level_crossings(const Flight& f, double level) {
    Crossings c;
    const double dy = level - f.y0;  // m, level above the start
    const double v = f.v0;
    if (f.g == 0.0) {
        if (v > 0.0 && dy >= 0.0) c.up = dy / v;
        if (v < 0.0 && dy <= 0.0) c.down = dy / v;
        return c;
    }
    const double disc = v * v - 2.0 * f.g * dy;  // m^2/s^2
    if (disc < 0.0) return c;                    // the apex stays below the level
    const double root = std::sqrt(disc);
    if (dy >= 0.0 && v > 0.0) c.up = 2.0 * dy / (v + root);
    if (dy <= 0.0 || v > 0.0) c.down = v >= 0.0 ? (v + root) / f.g : -2.0 * dy / (root - v);
    return c;
}

// The time in (lo, hi] where f changes sign, given f(lo) > 0 >= f(hi) and a single crossing.
// Newton steps are taken while they stay in the bracket and shrink fast enough, bisection otherwise.
// Once the bracket is down to kTimeTolerance (or 2 ulps of the time), its end with the smaller |f|
// is returned, but never the initial lo, so that every search makes progress.
template <class Fn, class Dfn>
double crossing_time(const Fn& f, const Dfn& df, double lo, double hi) {
    const double start = lo;
    double f_lo = kInf;   // f(lo) > 0; its value is unknown until lo moves
    double f_hi = -kInf;  // f(hi) <= 0; its value is unknown until hi moves
    double x = 0.5 * (lo + hi);
    double last_step = hi - lo;
    for (int i = 0; i < kMaxRootIterations; ++i) {
        const double ulp = std::nextafter(hi, kInf) - hi;
        if (hi - lo <= std::max(kTimeTolerance, 2.0 * ulp)) break;
        const double fx = f(x);
        if (fx > 0.0) {
            lo = x;
            f_lo = fx;
        } else {
            hi = x;
            f_hi = fx;
        }
        const double dfx = df(x);
        const double step = dfx != 0.0 ? fx / dfx : kInf;
        const double newton = x - step;
        if (std::isfinite(newton) && newton > lo && newton < hi && std::abs(step) < 0.5 * last_step) {
            if (std::abs(step) <= kTimeTolerance) return newton;
            last_step = std::abs(step);
            x = newton;
        } else {
            last_step = hi - lo;
            x = 0.5 * (lo + hi);
        }
    }
    return (lo > start && f_lo < -f_hi) ? lo : hi;
}

// The floor gap of one flight and its first two time derivatives.
struct FloorGap {
    const FloorMotion& floor;
    const Flight& flight;

    double value(double t) const { return flight.height(t) - floor.position(t); }   // m
    double rate(double t) const { return flight.velocity(t) - floor.velocity(t); }  // m/s
    double curvature(double t) const { return -flight.g - floor.acceleration(t); }  // m/s^2
};

// First time in (t0, t_limit] at which the flight meets the floor, or nullopt. starts_in_contact:
// the flight leaves the floor at t0 (G(t0) = 0, G'(t0) >= 0), so t0 itself is not a contact.
std::optional<double> first_floor_contact(const FloorMotion& floor, const Flight& flight, bool starts_in_contact, double t_limit) {
    const double A = floor.amplitude();
    if (A == 0.0) {  // still floor: an exact quadratic root
        const double t = flight.t0 + level_crossings(flight, 0.0).down;
        return t <= t_limit ? std::optional<double>(t) : std::nullopt;
    }
    const FloorGap gap{floor, flight};
    const double t0 = flight.t0;
    const Crossings top = level_crossings(flight, A);
    const double t_sure = flight.t0 + level_crossings(flight, -A).down;  // G <= 0 from here on
    const double t_end = std::min(t_limit, t_sure);

    std::array<std::pair<double, double>, 2> spans{};  // s, where y <= A
    int span_count = 0;
    if (flight.y0 <= A) {
        spans[span_count++] = {t0, t0 + top.up};
        if (top.up < kInf) spans[span_count++] = {t0 + top.down, kInf};
    } else if (top.down < kInf) {
        spans[span_count++] = {t0 + top.down, kInf};
    }

    for (int k = 0; k < span_count; ++k) {
        const double a = spans[k].first;
        const double b = std::min(spans[k].second, t_end);
        if (!(a < b)) continue;
        bool in_contact = starts_in_contact && a == t0;
        if (!in_contact && gap.value(a) <= 0.0) return a;
        long pieces = 0;
        for (double p = a; p < b;) {
            const double q = std::min(floor.next_knot(p), b);
            const double gq = gap.value(q);
            const bool convex = gap.curvature(0.5 * (p + q)) > 0.0;
            if (gq <= 0.0) {
                // Leaving the floor on a convex piece with G' >= 0, G cannot come back to zero:
                // a non-positive end value is rounding, not a contact.
                if (!(in_contact && convex)) {
                    return crossing_time([&](double t) { return gap.value(t); }, [&](double t) { return gap.rate(t); }, p, q);
                }
            } else if (convex && !in_contact && gap.rate(p) < 0.0 && gap.rate(q) > 0.0) {
                // Positive at both ends of a convex piece: look at its minimum for a graze.
                const double t_min =
                    crossing_time([&](double t) { return -gap.rate(t); }, [&](double t) { return -gap.curvature(t); }, p, q);
                if (gap.value(t_min) <= 0.0) {
                    return crossing_time([&](double t) { return gap.value(t); }, [&](double t) { return gap.rate(t); }, p, t_min);
                }
            }
            in_contact = false;
            p = q;
            if (++pieces > kMaxPiecesPerSearch) {
                throw std::runtime_error("vibrating floor reference: contact search does not end");
            }
        }
    }
    // The parabola reached -A before t_limit, so it met the floor by then; arriving here means the
    // contact is within rounding of that instant (floor at its lowest point).
    if (t_sure <= t_limit) return t_sure;
    return std::nullopt;
}

struct SpeedAccumulator {
    std::uint64_t count = 0;
    double sum = 0.0;     // m/s
    double sum_sq = 0.0;  // m^2/s^2

    void add(double speed) {
        ++count;
        sum += speed;
        sum_sq += speed * speed;
    }
    ImpactSpeedStats result() const {
        ImpactSpeedStats s;
        s.count = count;
        if (count > 0) {
            s.mean = sum / static_cast<double>(count);
            s.rms = std::sqrt(sum_sq / static_cast<double>(count));
        }
        return s;
    }
};

void require(bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("vibrating floor reference: ") + what);
}

void validate(const VibratingFloorCase& c) {
    require(std::isfinite(c.R) && c.R > 0.0, "R must be > 0");
    require(std::isfinite(c.g) && c.g >= 0.0, "g must be >= 0");
    require(std::isfinite(c.A) && c.A >= 0.0, "A must be >= 0");
    require(std::isfinite(c.F) && c.F > 0.0, "F must be > 0");
    require(std::isfinite(c.phase), "phase must be finite");
    require(std::isfinite(c.H) && c.H - 2.0 * c.R > c.A, "H - 2R must exceed A");
    require(std::isfinite(c.z0) && std::isfinite(c.v0), "z0 and v0 must be finite");
    require(c.C0_floor >= 0.0 && c.C0_ceiling >= 0.0, "C0 must be >= 0");
    require(c.V0_floor > 0.0 && c.V0_ceiling > 0.0, "V0 must be > 0");
    require(std::isfinite(c.duration) && c.duration >= 0.0, "duration must be >= 0");
    require(c.statistics_start >= 0.0 && c.statistics_start <= c.duration, "statistics_start must be in [0, duration]");
    require(c.chatter_speed >= 0.0, "chatter_speed must be >= 0");
    require(c.contact_tolerance >= 0.0, "contact_tolerance must be >= 0");
}

class Simulation {
public:
    explicit Simulation(const VibratingFloorCase& c) : c_(c), floor_(c.A, c.F, c.phase, c.g), y_top_(c.H - 2.0 * c.R) {}

    VibratingFloorStats run() {
        start();
        std::uint64_t steps = 0;  // rides and flights, including those ending in a graze
        while (t_ < c_.duration) {
            if (riding_) {
                ride();
            } else if (!fly()) {
                break;
            }
            if (++steps > c_.max_events) {
                throw std::runtime_error("vibrating floor reference: more events than max_events");
            }
        }
        finish();
        return std::move(stats_);
    }

private:
    void start() {
        y_ = c_.z0 - c_.R;
        v_ = c_.v0;
        const double gap0 = y_ - floor_.position(0.0);
        require(gap0 >= -c_.contact_tolerance, "the shot starts inside the floor");
        require(y_ - y_top_ <= c_.contact_tolerance, "the shot starts inside the ceiling");
        y_ = std::min(y_, y_top_);
        if (gap0 <= c_.contact_tolerance) floor_contact(0.0, v_, gap0);
    }

    // Rides on the floor until the floor's acceleration falls to -g, then leaves it with the
    // floor's velocity (the contact force of a sticking shot would turn negative there).
    void ride() {
        const double t_release = floor_.next_release(t_);
        if (t_release >= c_.duration) {
            t_ = c_.duration;
            y_ = floor_.position(t_);
            v_ = floor_.velocity(t_);
            return;
        }
        t_ = t_release;
        y_ = floor_.position(t_);
        v_ = floor_.velocity(t_);
        riding_ = false;
        leaving_floor_ = true;
        record({t_, VibratingFloorEventKind::floor_release, 0.0, y_ + c_.R, v_, v_, 0.0});
    }

    // One flight up to its next event; false when the run ends in this flight.
    bool fly() {
        const Flight flight{t_, y_, v_, c_.g};
        const double t_ceiling = t_ + level_crossings(flight, y_top_).up;
        const double t_limit = std::min(t_ceiling, c_.duration);
        const std::optional<double> t_floor = first_floor_contact(floor_, flight, leaving_floor_, t_limit);
        if (t_floor) {
            const double gap = flight.height(*t_floor) - floor_.position(*t_floor);
            floor_contact(*t_floor, flight.velocity(*t_floor), gap);
            return true;
        }
        if (t_ceiling <= c_.duration) {
            ceiling_contact(t_ceiling, flight);
            return true;
        }
        t_ = c_.duration;
        y_ = flight.height(t_);
        v_ = flight.velocity(t_);
        return false;
    }

    // The shot meets the floor at t with velocity v_in (m/s); gap (m) is the parabola's gap there.
    // The shot is placed exactly on the floor (moving it by |gap| ~ 1e-15 m) so the next flight
    // starts with G = 0.
    void floor_contact(double t, double v_in, double gap) {
        t_ = t;
        y_ = floor_.position(t);
        const double v_floor = floor_.velocity(t);
        const double u = v_in - v_floor;  // m/s, relative normal velocity (< 0: approaching)
        double u_after = u;               // a touch without approach (graze) changes nothing
        if (u < 0.0) {
            const double speed = -u;
            u_after = restitution(c_.C0_floor, c_.V0_floor, speed) * speed;
            // An approach slower than chatter_speed is a touch (often rounding, ~1e-16 m/s), not
            // an impact: it changes the velocity like one but is neither counted nor recorded.
            if (speed >= c_.chatter_speed) {
                if (t >= c_.statistics_start) floor_speeds_.add(speed);
                record({t, VibratingFloorEventKind::floor_impact, speed, y_ + c_.R, v_in, v_floor + u_after, gap});
            }
        }
        v_ = v_floor + u_after;
        // Chatter rule: a rebound slower than chatter_speed on a floor that accelerates upwards
        // faster than -g (G'' < 0) would be caught again at once, an endless (Zeno) sequence of
        // ever smaller bounces that converges to the shot sticking. We stick it at once: it rides
        // with the floor until the floor's acceleration falls to -g (see ride()).
        const double floor_acceleration = floor_.acceleration(t);  // m/s^2
        if (u_after < c_.chatter_speed && floor_acceleration > -c_.g) {
            riding_ = true;
            v_ = v_floor;
            ++stats_.floor_captures;
            record({t, VibratingFloorEventKind::floor_capture, 0.0, y_ + c_.R, v_in, v_, gap});
        } else {
            leaving_floor_ = true;
        }
    }

    void ceiling_contact(double t, const Flight& flight) {
        const double v_in = flight.velocity(t);
        const double gap = y_top_ - flight.height(t);
        t_ = t;
        y_ = y_top_;
        v_ = v_in;
        leaving_floor_ = false;
        if (v_in > 0.0) {
            v_ = -restitution(c_.C0_ceiling, c_.V0_ceiling, v_in) * v_in;
            if (t >= c_.statistics_start) ceiling_speeds_.add(v_in);
            record({t, VibratingFloorEventKind::ceiling_impact, v_in, y_ + c_.R, v_in, v_, gap});
        }
    }

    void record(const VibratingFloorEvent& e) {
        ++stats_.events_total;
        if (c_.on_event) c_.on_event(e);
        if (stats_.first_events.size() < c_.max_recorded_events) stats_.first_events.push_back(e);
    }

    void finish() {
        stats_.floor = floor_speeds_.result();
        stats_.ceiling = ceiling_speeds_.result();
        stats_.counted_time = c_.duration - c_.statistics_start;
        stats_.final_z = y_ + c_.R;
        stats_.final_v = v_;
        stats_.final_riding = riding_;
    }

    const VibratingFloorCase& c_;
    FloorMotion floor_;
    double y_top_;  // m, ceiling height for the shot's lowest point

    double t_ = 0.0;  // s
    double y_ = 0.0;  // m, lowest point of the shot
    double v_ = 0.0;  // m/s
    bool riding_ = false;
    bool leaving_floor_ = false;  // the current flight starts on the floor (G = 0, G' >= 0)
    SpeedAccumulator floor_speeds_;
    SpeedAccumulator ceiling_speeds_;
    VibratingFloorStats stats_;
};

}  // namespace

double VibratingFloorStats::floor_rate() const { return counted_time > 0.0 ? static_cast<double>(floor.count) / counted_time : 0.0; }

double VibratingFloorStats::ceiling_rate() const { return counted_time > 0.0 ? static_cast<double>(ceiling.count) / counted_time : 0.0; }

VibratingFloorStats simulate_vibrating_floor(const VibratingFloorCase& c) {
    validate(c);
    return Simulation(c).run();
}

}  // namespace peensim::testing
