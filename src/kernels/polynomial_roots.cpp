#include "kernels/polynomial_roots.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "common/float_limits.h"

namespace peensim {

namespace {

// |p(t)| below this many eps times sum |c_i| |t|^i is zero: Horner's own error is at most
// 2 * degree * eps times that sum, and a critical point located to an ulp adds about as much again.
constexpr double kZeroSlack = 16.0;
// A leading term below this fraction of the others (in magnitude over [a, b]) is dropped: it
// moves p by less than its rounding, and a tiny leading coefficient only slows the recursion.
constexpr double kNegligibleTerm = 1e-3 * kEps;
// One boundary per end plus the interior critical points (at most degree - 1 = 3, but a derivative
// that is zero to within rounding over a piece can report both ends of it).
constexpr int kMaxBoundaries = 8;

int sign_of(double x) { return (x > 0.0) - (x < 0.0); }

double abs_sum(const Polynomial& p, double t) {
    const double at = std::fabs(t);
    double s = std::fabs(p.c[static_cast<std::size_t>(p.degree)]);
    for (int i = p.degree - 1; i >= 0; --i) s = s * at + std::fabs(p.c[static_cast<std::size_t>(i)]);
    return s;
}

bool is_zero_at(const Polynomial& p, double t, double value) { return std::fabs(value) <= kZeroSlack * kEps * abs_sum(p, t); }

void value_and_slope(const Polynomial& p, double t, double& value, double& slope) {
    double v = p.c[static_cast<std::size_t>(p.degree)], d = 0.0;
    for (int i = p.degree - 1; i >= 0; --i) {
        d = d * t + v;
        v = v * t + p.c[static_cast<std::size_t>(i)];
    }
    value = v;
    slope = d;
}

Polynomial trimmed(const Polynomial& in, double a, double b) {
    Polynomial p = in;
    p.degree = std::clamp(p.degree, 0, 4);
    const double m = std::max(std::fabs(a), std::fabs(b));
    while (p.degree > 0) {
        double lead = std::fabs(p.c[static_cast<std::size_t>(p.degree)]);
        for (int i = 0; i < p.degree; ++i) lead *= m;
        double rest = 0.0;
        for (int i = p.degree - 1; i >= 0; --i) rest = rest * m + std::fabs(p.c[static_cast<std::size_t>(i)]);
        if (p.c[static_cast<std::size_t>(p.degree)] != 0.0 && lead > kNegligibleTerm * rest) break;
        p.c[static_cast<std::size_t>(p.degree)] = 0.0;
        --p.degree;
    }
    return p;
}

// The root of p in (lo, hi), where p is monotone and f_lo, f_hi have strictly opposite signs:
// Newton from the secant point, falling back to bisection whenever a step would leave the bracket
// or fails to halve it, so convergence is never slower than bisection.
double refine(const Polynomial& p, double lo, double hi, double f_lo, double f_hi) {
    const int s_lo = sign_of(f_lo);
    const double floor = std::numeric_limits<double>::min();
    double x = lo - f_lo * (hi - lo) / (f_hi - f_lo);
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    double step_before_last = hi - lo, last_step = hi - lo;
    for (int iter = 0; iter < 200; ++iter) {
        double f, df;
        value_and_slope(p, x, f, df);
        // Below Horner's own rounding, f is noise: x is as good as p allows. (Without this stop,
        // Newton dithers there and the bisection fallback then halves a wide bracket ~50 times.)
        if (std::fabs(f) <= 2.0 * kEps * abs_sum(p, x)) return x;
        if (sign_of(f) == s_lo)
            lo = x;
        else
            hi = x;
        double next = df != 0.0 ? x - f / df : lo - 1.0;
        const bool newton_inside = next > lo && next < hi;
        if (!newton_inside || std::fabs(next - x) > 0.5 * step_before_last) next = 0.5 * (lo + hi);
        step_before_last = last_step;
        last_step = std::fabs(next - x);
        if (last_step <= 2.0 * kEps * std::fabs(next) + floor) return next;
        if (hi - lo <= 2.0 * kEps * std::max(std::fabs(lo), std::fabs(hi)) + floor) return 0.5 * (lo + hi);
        x = next;
    }
    return x;
}

RootKind classify(int before, int after) {
    if (before >= 0 && after < 0) return RootKind::falling;
    if (before < 0 && after >= 0) return RootKind::rising;
    if (before < 0 && after < 0) return RootKind::touch_from_below;
    return RootKind::touch_from_above;
}

bool accepted(RootKind kind, RootFilter filter) {
    return filter == RootFilter::any || kind == RootKind::falling || kind == RootKind::touch_from_above;
}

// The interior critical points of a cubic (the roots of its derivative q, a quadratic) in
// closed form, into x after x[n - 1]; returns the new n. They only bound the cubic's monotone
// pieces, so the ~sqrt(eps) error of a near-double root here is harmless: the cubic's own roots
// are refined on those pieces.
int quadratic_boundaries(const Polynomial& q, double b, double* x, int n) {
    const double A = q.c[2], B = q.c[1], C = q.c[0];
    const double disc = B * B - 4.0 * A * C;
    if (disc < 0.0) return n;
    const double w = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    double r1 = w / A, r2 = w != 0.0 ? C / w : r1;
    if (r1 > r2) std::swap(r1, r2);
    for (double r : {r1, r2})
        if (r > x[n - 1] && r < b) x[n++] = r;
    return n;
}

// Roots of p in [a, b] into out (capacity kMaxBoundaries), increasing; with first_only, stops at
// the first root accepted by `filter` and returns just that one. Returns the count.
// True if p keeps one strict sign on [a, b], clear of rounding: the Taylor expansion about the
// middle, p(m + s) = q0 + q1 s + ..., has |q0| above sum |qk| h^k (h the half-width) by a margin
// that covers the expansion's own rounding. Most gap polynomials the kernels build have no root in
// their window; this settles them without isolating anything.
bool clearly_one_sign(const Polynomial& p, double a, double b) {
    const double m = 0.5 * (a + b), h = 0.5 * (b - a);
    std::array<double, 5> q = p.c;
    for (int k = 0; k < p.degree; ++k)  // Taylor shift by repeated synthetic division
        for (int i = p.degree - 1; i >= k; --i) q[static_cast<std::size_t>(i)] += m * q[static_cast<std::size_t>(i + 1)];
    double reach = 0.0, hk = 1.0;
    for (int k = 1; k <= p.degree; ++k) {
        hk *= h;
        reach += std::fabs(q[static_cast<std::size_t>(k)]) * hk;
    }
    const double margin = 64.0 * kEps * (abs_sum(p, std::max(std::fabs(a), std::fabs(b))) + reach);
    return std::fabs(q[0]) > reach + margin;
}

int solve(const Polynomial& p_in, double a, double b, PolynomialRoot* out, bool first_only, RootFilter filter) {
    const Polynomial p = trimmed(p_in, a, b);
    if (p.degree >= 2 && clearly_one_sign(p, a, b)) return 0;
    double x[kMaxBoundaries];
    int n = 0;
    x[n++] = a;
    if (p.degree == 3) {
        n = quadratic_boundaries(p.derivative(), b, x, n);
    } else if (p.degree >= 2) {
        PolynomialRoot critical[kMaxBoundaries];
        const int nc = solve(p.derivative(), a, b, critical, false, RootFilter::any);
        for (int i = 0; i < nc && n < kMaxBoundaries - 1; ++i)
            if (critical[i].t > x[n - 1] && critical[i].t < b) x[n++] = critical[i].t;
    }
    if (b > a) x[n++] = b;

    double f[kMaxBoundaries];
    bool zero[kMaxBoundaries];
    for (int i = 0; i < n; ++i) {
        f[i] = p(x[i]);
        zero[i] = is_zero_at(p, x[i], f[i]);
    }
    // The sign of p inside the piece between boundaries i and j (adjacent), seen from i: the
    // sign at j unless p is zero there too, then the sign at the middle.
    auto sign_inside = [&](int i, int j) {
        if (!zero[j]) return sign_of(f[j]);
        return sign_of(p(0.5 * (x[i] + x[j])));
    };

    int count = 0;
    // Records a root in order; true when the search is over (the first accepted one was asked for).
    auto found = [&](const PolynomialRoot& r) {
        if (!first_only) {
            out[count++] = r;
            return false;
        }
        if (!accepted(r.kind, filter)) return false;
        out[0] = r;
        count = 1;
        return true;
    };
    for (int i = 0; i < n; ++i) {
        if (zero[i]) {
            int before = i > 0 ? sign_inside(i, i - 1) : 0;
            int after = i + 1 < n ? sign_inside(i, i + 1) : 0;
            if (i == 0) before = -after;
            if (i == n - 1 && i > 0) after = -before;
            if (found({x[i], classify(before, after)})) return count;
        }
        if (i + 1 < n && !zero[i] && !zero[i + 1] && sign_of(f[i]) != sign_of(f[i + 1])) {
            if (found({refine(p, x[i], x[i + 1], f[i], f[i + 1]), f[i] > 0.0 ? RootKind::falling : RootKind::rising})) return count;
        }
    }
    return count;
}

}  // namespace

void real_roots_in(const Polynomial& p, double a, double b, PolynomialRoots& out) {
    out.count = 0;
    if (!(a <= b)) return;
    PolynomialRoot roots[kMaxBoundaries];
    const int n = solve(p, a, b, roots, false, RootFilter::any);
    for (int i = 0; i < n && out.count < static_cast<int>(out.root.size()); ++i) out.root[static_cast<std::size_t>(out.count++)] = roots[i];
}

bool first_root_in(const Polynomial& p, double a, double b, PolynomialRoot& out, RootFilter filter) {
    if (!(a <= b)) return false;
    PolynomialRoot roots[kMaxBoundaries];
    if (solve(p, a, b, roots, true, filter) == 0) return false;
    out = roots[0];
    return true;
}

}  // namespace peensim
