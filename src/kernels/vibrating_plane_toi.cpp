#include "kernels/vibrating_plane_toi.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "common/float_limits.h"
#include "common/sim_time.h"
#include "kernels/polynomial_roots.h"

namespace peensim {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
// A gap below this many eps times the magnitude of the terms it is summed from is a touch: the
// rounding of those terms (positions of ~0.1 m, the radius, the amplitude) is a few eps of it.
constexpr double kTouchSlack = 16.0;
// Below this many eps of that magnitude the gap (or its slope) is rounding noise: Newton stops.
constexpr double kNoiseSlack = 4.0;
// The band |static gap| <= |A n.a| is widened by this many eps of the magnitudes over the whole
// interval (more than the touch tolerance), so rounding cannot drop a touch at its edge.
constexpr double kBandSlack = 64.0;
// Newton halves its bracket at least every other step; 200 steps exhaust any double bracket.
constexpr int kMaxIterations = 200;

struct GapValue {
    double h, dh, ddh;  // m, m/s, m/s^2
};

// The gap near a reference time t_ref as a function of v = t - t_ref (s): the centre's distance to
// the plane at rest less R is the quadratic e0 + e1 v + e2 v^2; the plate adds -amp sin(theta0 + w v).
// Working from t_ref keeps v, and so the rounding of w v, to the few periods being searched.
struct LocalGap {
    double e0 = 0.0, e1 = 0.0, e2 = 0.0;  // m, m/s, m/s^2
    double amp = 0.0;                     // m, A n.a
    double w = 0.0;                       // rad/s
    double theta0 = 0.0;                  // rad, phase at t_ref
    double size = 0.0;                    // m, magnitude of the terms e0 is the difference of

    GapValue at(double v) const {
        const double th = theta0 + w * v;
        const double s = std::sin(th), c = std::cos(th);
        return {e0 + v * (e1 + v * e2) - amp * s, e1 + 2.0 * e2 * v - amp * w * c, 2.0 * e2 + amp * w * w * s};
    }
    double curvature(double v) const { return 2.0 * e2 + amp * w * w * std::sin(theta0 + w * v); }
    double magnitude(double v) const { return size + std::fabs(v * e1) + std::fabs(v * v * e2); }
    double touch_tolerance(double v) const { return kTouchSlack * kEps * magnitude(v); }
    double noise(double v) const { return kNoiseSlack * kEps * magnitude(v); }
    double slope_noise(double v) const { return kNoiseSlack * kEps * (std::fabs(e1) + std::fabs(2.0 * e2 * v) + std::fabs(amp * w)); }
};

LocalGap local_gap(const Trajectory& path, double radius, const VibratingPlane& plane, double amp, double w, double t_ref) {
    const Vec3 p = path.position(t_ref);
    LocalGap g;
    g.e0 = plane.normal.dot(p - plane.point_m) - radius;
    g.e1 = plane.normal.dot(path.velocity(t_ref));
    g.e2 = 0.5 * plane.normal.dot(path.g);
    g.amp = amp;
    g.w = w;
    g.theta0 = plane.phase(t_ref);
    g.size = p.norm() + plane.point_m.norm() + radius + std::fabs(amp);
    return g;
}

// The zero of f in (lo, hi), where f(lo) and f(hi) have strictly opposite signs and f changes sign
// once: Newton from the secant point, falling back to bisection whenever a step would leave the
// bracket or fails to halve it. `eval(x, f, df, noise)`. Returns a point where |f| is below its
// rounding noise, or, once the bracket is down to the resolution of the absolute time t_ref + x,
// its end on lo's side (for a falling gap: the outside, where the shot has not yet touched).
template <class Eval>
double refine(const Eval& eval, double lo, double hi, double f_lo, double f_hi, double t_ref, int& iterations) {
    const bool lo_positive = f_lo > 0.0;
    const double floor = std::numeric_limits<double>::min();
    double x = lo - f_lo * (hi - lo) / (f_hi - f_lo);
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    double step_before_last = hi - lo, last_step = hi - lo;
    for (int iter = 0; iter < kMaxIterations; ++iter) {
        ++iterations;
        double f, df, noise;
        eval(x, f, df, noise);
        if (std::fabs(f) <= noise) return x;
        if ((f > 0.0) == lo_positive)
            lo = x;
        else
            hi = x;
        const double resolution = 2.0 * kEps * (std::fabs(t_ref) + std::fabs(hi)) + floor;
        if (hi - lo <= resolution) return lo;
        double next = df != 0.0 ? x - f / df : lo - 1.0;
        if (!(next > lo && next < hi) || std::fabs(next - x) > 0.5 * step_before_last) next = 0.5 * (lo + hi);
        step_before_last = last_step;
        last_step = std::fabs(next - x);
        // Newton converging from one side never closes the bracket: stop when its steps vanish.
        if (last_step <= resolution) return next;
        x = next;
    }
    return lo;
}

// The knots of one window: where h'' = 2 e2 + amp w^2 sin(theta) changes sign, at the phases where
// sin(theta) = -2 e2 / (amp w^2), two per period (none if that is outside (-1, 1): then the plate's
// acceleration never beats gravity's and h keeps the convexity of e2 throughout).
struct Knots {
    std::array<double, 2> offset{};  // rad, phase advance from theta0 to each knot, in [0, 2 pi)
    int count = 0;
    double w = 0.0;

    explicit Knots(const LocalGap& g) : w(g.w) {
        if (g.amp == 0.0 || g.w == 0.0) return;
        const double s = -2.0 * g.e2 / (g.amp * g.w * g.w);
        if (!(std::fabs(s) < 1.0)) return;
        const double psi = std::asin(s);
        const double x = g.theta0 - kTwoPi * std::floor(g.theta0 / kTwoPi);
        for (double target : {psi, M_PI - psi}) {
            double d = target - x;
            d -= kTwoPi * std::floor(d / kTwoPi);
            offset[static_cast<std::size_t>(count++)] = d;
        }
        if (offset[0] > offset[1]) std::swap(offset[0], offset[1]);
    }
    // The k-th knot time (s from t_ref), increasing with k.
    double time(long k) const { return (offset[static_cast<std::size_t>(k & 1)] + kTwoPi * static_cast<double>(k >> 1)) / w; }
};

// The earliest contact in [0, v_end] of one band window, into v_hit. `skip`: the window starts at
// a touch that is separating (right after a bounce), so the rise of the gap is not a contact.
bool search_window(const LocalGap& g, double v_end, bool skip, double t_ref, PlaneToiWork& work, double& v_hit) {
    auto hit = [&](double v) {
        v_hit = v;
        return true;
    };
    auto gap_eval = [&](double v, double& f, double& df, double& noise) {
        const GapValue value = g.at(v);
        f = value.h;
        df = value.dh;
        noise = g.noise(v);
    };
    auto slope_eval = [&](double v, double& f, double& df, double& noise) {
        const GapValue value = g.at(v);
        f = value.dh;
        df = value.ddh;
        noise = g.slope_noise(v);
    };
    // The crossing in (lo, hi) of a gap positive at lo and negative at hi.
    auto crossing = [&](double lo, const GapValue& at_lo, double hi, const GapValue& at_hi) {
        return refine(gap_eval, lo, hi, at_lo.h, at_hi.h, t_ref, work.iterations);
    };
    // The extreme in (lo, hi) of the gap, whose slope has opposite signs at the ends.
    auto extreme = [&](double lo, const GapValue& at_lo, double hi, const GapValue& at_hi) {
        return refine(slope_eval, lo, hi, at_lo.dh, at_hi.dh, t_ref, work.iterations);
    };

    const Knots knots(g);
    long k = 0;
    double va = 0.0;
    GapValue at_a = g.at(va);
    if (!skip && at_a.h <= g.touch_tolerance(va)) return hit(va);
    while (va < v_end) {
        double vb = v_end;
        if (knots.count > 0) {
            while (knots.time(k) <= va) ++k;
            vb = std::min(vb, knots.time(k));
        }
        ++work.pieces;
        const GapValue at_b = g.at(vb);
        const bool convex = knots.count > 0 ? g.curvature(0.5 * (va + vb)) >= 0.0 : g.e2 >= 0.0;

        if (skip) {
            if (at_a.dh >= 0.0 && (convex || at_b.dh > 0.0)) {  // still rising throughout
                va = vb;
                at_a = at_b;
                continue;
            }
            // The gap peaks at vc (a concave piece whose slope turns negative): from there on it
            // closes, and a peak within the touch tolerance means the shot never really left.
            skip = false;
            double vc = va;
            GapValue at_c = at_a;
            if (at_a.dh > 0.0) {
                vc = at_b.dh < 0.0 ? extreme(va, at_a, vb, at_b) : vb;
                at_c = vc < vb ? g.at(vc) : at_b;
            }
            if (at_c.h <= g.touch_tolerance(vc)) return hit(vc);
            va = vc;
            at_a = at_c;
            if (!(va < vb)) continue;
        }

        // Here h(va) is above the touch tolerance. A convex or concave piece crosses zero at most
        // once from above (its part below zero, or above, is one interval).
        if (at_b.h < 0.0) return hit(crossing(va, at_a, vb, at_b));
        if (convex && at_a.dh < 0.0 && at_b.dh > 0.0) {
            // An interior minimum. Convexity puts h above both end tangents, so above their
            // intersection: most minima are cleared without locating them.
            const double span = vb - va;
            const double s = std::clamp((at_b.h - at_a.h - at_b.dh * span) / (at_a.dh - at_b.dh), 0.0, span);
            const double tol = std::max(g.touch_tolerance(va), g.touch_tolerance(vb));
            if (at_a.h + at_a.dh * s <= tol) {
                const double vc = extreme(va, at_a, vb, at_b);
                const GapValue at_c = g.at(vc);
                if (at_c.h < 0.0 && vc > va) return hit(crossing(va, at_a, vc, at_c));
                if (at_c.h <= g.touch_tolerance(vc)) return hit(vc);  // a graze: a double root
            }
        }
        // Closing to within the tolerance at vb: a touch (or a crossing just after, within rounding).
        if (at_b.h <= g.touch_tolerance(vb)) return hit(vb);
        va = vb;
        at_a = at_b;
    }
    return false;
}

void describe(const Trajectory& path, const VibratingPlane& plane, double t, PlaneContact& out) {
    const double th = plane.phase(t);
    const double w = plane.angular_frequency();
    const double s = std::sin(th), c = std::cos(th);
    const Vec3 p = path.position(t);
    const Vec3 q = plane.point_m + (plane.amplitude_m * s) * plane.axis;
    out.time = t;
    out.point = p - plane.normal.dot(p - q) * plane.normal;
    out.normal = plane.normal;
    out.plate_velocity = (plane.amplitude_m * w * c) * plane.axis;
    out.plate_acceleration = (-plane.amplitude_m * w * w * s) * plane.axis;
}

}  // namespace

double VibratingPlane::angular_frequency() const { return kTwoPi * frequency_hz; }

double VibratingPlane::phase(double t) const { return kTwoPi * SimTime{t, 0.0}.cycle_fraction(frequency_hz) + phase_rad; }

double VibratingPlane::displacement(double t) const { return amplitude_m * std::sin(phase(t)); }

Vec3 VibratingPlane::velocity(double t) const { return (amplitude_m * angular_frequency() * std::cos(phase(t))) * axis; }

Vec3 VibratingPlane::acceleration(double t) const {
    const double w = angular_frequency();
    return (-amplitude_m * w * w * std::sin(phase(t))) * axis;
}

double vibrating_plane_gap(const Trajectory& path, double radius, const VibratingPlane& plane, double t) {
    const double amp = plane.amplitude_m * plane.normal.dot(plane.axis);
    return plane.normal.dot(path.position(t) - plane.point_m) - radius - amp * std::sin(plane.phase(t));
}

ToiStatus vibrating_plane_toi(const Trajectory& path, double radius, const VibratingPlane& plane, double t_begin, double t_end,
                              PlaneContact& out, PlaneToiWork* work) {
    PlaneToiWork scratch;
    PlaneToiWork& tally = work != nullptr ? *work : scratch;
    if (!(t_end >= t_begin)) return ToiStatus::miss;
    const double amp = plane.amplitude_m * plane.normal.dot(plane.axis);
    const double w = plane.angular_frequency();

    // The state at t_begin, read as in sphere_triangle_toi (see toi_status.h).
    const LocalGap start = local_gap(path, radius, plane, amp, w, t_begin);
    const GapValue now = start.at(0.0);
    const double band = kStartTouchFraction * radius;
    bool separating = false;
    if (now.h < band) {
        describe(path, plane, t_begin, out);
        if (now.h < -band) return ToiStatus::overlapping;
        // Approaching, or at rest relative to the plate and pulled in (its acceleration beats
        // gravity's, or gravity pulls towards it): an impact now.
        if (now.dh < 0.0 || (now.dh == 0.0 && now.ddh < 0.0)) return ToiStatus::impact;
        separating = true;
    }

    // Windows where the static gap is within the band the plate sweeps: outside them h > 0.
    const double span = t_end - t_begin;
    const double top = std::fabs(amp) + kBandSlack * kEps * (start.size + std::fabs(start.e1) * span + std::fabs(start.e2) * span * span);
    Polynomial above;  // static gap less the band's top: negative inside the band
    above.degree = 2;
    above.c = {start.e0 - top, start.e1, start.e2, 0.0, 0.0};
    PolynomialRoots roots;
    real_roots_in(above, 0.0, span, roots);
    std::array<double, 16> window{};  // [begin, end] pairs, u = t - t_begin
    int count = 0;
    auto add = [&](double a, double b) {
        window[static_cast<std::size_t>(count++)] = a;
        window[static_cast<std::size_t>(count++)] = b;
    };
    bool inside = start.e0 <= top;
    double opened = 0.0;
    for (int i = 0; i < roots.count; ++i) {
        const PolynomialRoot& r = roots.root[static_cast<std::size_t>(i)];
        const bool enters = r.kind == RootKind::falling || r.kind == RootKind::touch_from_below;
        if (enters && !inside) {
            opened = r.t;
            inside = true;
        } else if (r.kind == RootKind::rising && inside) {
            add(opened, r.t);
            inside = false;
        } else if (r.kind == RootKind::touch_from_above && !inside) {
            add(r.t, r.t);
        }
    }
    if (inside) add(opened, span);

    constexpr double kInf = std::numeric_limits<double>::infinity();
    for (int i = 0; i < count; i += 2) {
        const double ua = window[static_cast<std::size_t>(i)], ub = window[static_cast<std::size_t>(i + 1)];
        ++tally.windows;
        // Window ends rounded outwards: the band's slack covers the rounding of t_begin + u.
        const double t_ref = ua == 0.0 ? t_begin : std::max(t_begin, std::nextafter(t_begin + ua, -kInf));
        const double t_stop = ub >= span ? t_end : std::min(t_end, std::nextafter(t_begin + ub, kInf));
        const bool from_start = t_ref == t_begin;
        const LocalGap g = from_start ? start : local_gap(path, radius, plane, amp, w, t_ref);
        double v = 0.0;
        if (search_window(g, t_stop - t_ref, separating && from_start, t_ref, tally, v)) {
            describe(path, plane, t_ref + v, out);
            return ToiStatus::impact;
        }
    }
    return ToiStatus::miss;
}

}  // namespace peensim
