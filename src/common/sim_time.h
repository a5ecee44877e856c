// Simulated time kept as an unevaluated sum hi + lo (compensated summation), so that adding
// ~2 million steps of ~30 us over a 60 s run keeps the time, and the sonotrode phase derived
// from it, accurate to ~1e-15 s instead of drifting by ~1e-9 s (a visible phase error at 20 kHz).
#pragma once

#include <cmath>

namespace peensim {

struct SimTime {
    double hi = 0.0;  // s
    double lo = 0.0;  // s, rounding error of hi

    double seconds() const { return hi + lo; }

    void advance(double dt) {
        // Knuth's TwoSum: s + e == hi + dt exactly.
        const double s = hi + dt;
        const double bp = s - hi;
        const double e = (hi - (s - bp)) + (dt - bp);
        hi = s;
        lo += e;
        // Renormalise so that |lo| stays below an ulp of hi.
        const double s2 = hi + lo;
        lo = lo - (s2 - hi);
        hi = s2;
    }

    // Fraction of a cycle of frequency F (Hz) elapsed at this time plus an offset (s), in [0, 1).
    // Written so that the large part F*hi is reduced before the small parts are added.
    double cycle_fraction(double F, double offset_s = 0.0) const {
        // F * hi exactly, as p + e (TwoProduct with a fused multiply-add): at 60 s and 20 kHz the
        // rounding of a plain product alone would be ~1e-9 rad of phase.
        const double p = F * hi;
        const double e = std::fma(F, hi, -p);
        double whole;
        const double f_hi = std::modf(p, &whole);
        const double f = f_hi + (e + F * (lo + offset_s));
        return f - std::floor(f);
    }
};

}  // namespace peensim
