// Real roots of a polynomial of degree <= 4 in a closed interval, the kernel of every exact
// time of impact. Roots are isolated by recursion on derivatives (the roots of p' cut [a, b] into
// pieces on which p is monotone) and refined by safeguarded Newton; a critical point where p is
// zero to within rounding is a double root (a grazing touch), which plain sign tests would miss.
// Pure computation: no allocation, no I/O.
#pragma once

#include <array>

namespace peensim {

// c[0] + c[1] t + c[2] t^2 + c[3] t^3 + c[4] t^4; coefficients above `degree` are ignored.
struct Polynomial {
    std::array<double, 5> c{};
    int degree = 0;  // 0..4

    double operator()(double t) const {
        double v = c[static_cast<std::size_t>(degree)];
        for (int i = degree - 1; i >= 0; --i) v = v * t + c[static_cast<std::size_t>(i)];
        return v;
    }
    Polynomial derivative() const {
        Polynomial d;
        d.degree = degree > 0 ? degree - 1 : 0;
        for (int i = 1; i <= degree; ++i) d.c[static_cast<std::size_t>(i - 1)] = i * c[static_cast<std::size_t>(i)];
        return d;
    }
};

// How p behaves around a root, seen in the direction of increasing t. A root at an end of the
// interval is classified by the side inside it (p < 0 just after a: `falling`).
enum class RootKind : unsigned char {
    falling,           // + to -
    rising,            // - to +
    touch_from_above,  // p >= 0 on both sides: a double root at a minimum (or p == 0 throughout)
    touch_from_below,  // p <= 0 on both sides: a double root at a maximum
};

struct PolynomialRoot {
    double t = 0.0;
    RootKind kind = RootKind::falling;
};

// Which roots first_root_in may return.
enum class RootFilter : unsigned char {
    any,
    // falling or touch_from_above: the moments p, a gap function, reaches zero from above.
    entering,
};

// Room for 8 roots: a degree-4 polynomial has at most 4, but one that is zero to within rounding
// over a piece reports both ends of it.
struct PolynomialRoots {
    std::array<PolynomialRoot, 8> root{};
    int count = 0;
};

// All real roots of p in [a, b] (a <= b), in increasing order, each to about an ulp; a point
// where |p| is below the rounding error of evaluating p there counts as a root. Leading
// coefficients that cannot change p by more than rounding on [a, b] are dropped first.
void real_roots_in(const Polynomial& p, double a, double b, PolynomialRoots& out);

// The earliest root in [a, b] accepted by `filter`; stops refining as soon as it is found.
bool first_root_in(const Polynomial& p, double a, double b, PolynomialRoot& out, RootFilter filter = RootFilter::any);

}  // namespace peensim
