// When, within a step, did a shot first touch a surface? The stepping scheme detects contacts
// at the end of a step; these functions go back to the exact moment of first touch, so that
// rebounds happen at the right time, position and surface velocity (at the exact sonotrode
// phase). A gap function g(u) (m) is the distance between the shot surface and the contact
// plane, u (s) the offset from the step start; g < 0 means overlap.
#pragma once

#include <cmath>
#include <optional>

namespace peensim {

// Gap as a quadratic of the time s = u_end - u before the step end: g = c0 + c1 s + c2 s^2.
// Returns the earliest u in [u_lo, u_end] with g <= 0, or nothing if the gap stays positive.
inline std::optional<double> first_touch_quadratic(double c0, double c1, double c2, double u_lo, double u_end) {
    const double s_max = u_end - u_lo;
    auto gap = [&](double s) { return c0 + s * (c1 + s * c2); };
    if (gap(s_max) <= 0.0) return u_lo;  // already touching at the start of the interval
    // Largest root in [0, s_max): the crossing closest to the interval's start.
    double best = -1.0;
    auto consider = [&](double s) {
        if (s >= 0.0 && s <= s_max && s > best) best = s;
    };
    if (std::abs(c2) * s_max < 1e-12 * (std::abs(c1) + 1e-300)) {
        if (c1 != 0.0) consider(-c0 / c1);
    } else {
        const double disc = c1 * c1 - 4.0 * c2 * c0;
        if (disc >= 0.0) {
            const double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
            if (q != 0.0) {
                consider(q / c2);
                consider(c0 / q);
            } else {
                consider(0.0);
            }
        }
    }
    if (best < 0.0) return gap(0.0) <= 0.0 ? std::optional<double>(u_end) : std::nullopt;
    return u_end - best;
}

// Earliest u in [u_lo, u_end] with gap(u) <= 0 for a smooth gap function sampled every
// `max_sample_s` (s) at least, then refined by regula falsi (Illinois) to `tolerance_s`.
// Used for the vibrating sonotrode, whose gap oscillates within a step: sampling 32 times a
// period finds every crossing except grazes shallower than ~0.5 % of the amplitude.
//
// `leaving`: the shot has just rebounded from this very surface at u_lo, so a gap of ~0 there is
// that contact, not a new one: the search starts once the gap has opened, and finds the surface
// catching up with the shot again later in the step (a vibrating plate accelerates at ~1e5 g).
template <class Gap>
std::optional<double> first_touch_sampled(const Gap& gap, double u_lo, double u_end, double max_sample_s, double tolerance_s,
                                          bool leaving = false) {
    double a = u_lo, ga = gap(a);
    if (ga <= 0.0 && !leaving) return a;
    const int samples = std::max(1, static_cast<int>(std::ceil((u_end - u_lo) / max_sample_s)));
    for (int k = 1; k <= samples; ++k) {
        const double b = k == samples ? u_end : u_lo + (u_end - u_lo) * k / samples;
        const double gb = gap(b);
        if (gb > 0.0 || ga <= 0.0) {
            a = b;
            ga = gb;
            continue;
        }
        // Bracket [a, b] with ga > 0 >= gb: return the right end of the final bracket, so the
        // returned time is never before the touch (the shot is at or just inside the surface).
        double lo = a, hi = b, glo = ga, ghi = gb;
        int side = 0;
        for (int it = 0; it < 100 && hi - lo > tolerance_s; ++it) {
            double m = (lo * ghi - hi * glo) / (ghi - glo);
            if (!(m > lo && m < hi)) m = 0.5 * (lo + hi);
            const double gm = gap(m);
            if (gm > 0.0) {
                lo = m, glo = gm;
                if (side == -1) ghi *= 0.5;
                side = -1;
            } else {
                hi = m, ghi = gm;
                if (side == 1) glo *= 0.5;
                side = 1;
            }
        }
        return hi;
    }
    return std::nullopt;
}

}  // namespace peensim
