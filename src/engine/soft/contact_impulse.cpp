#include "engine/soft/contact_impulse.h"

#include <algorithm>
#include <cmath>

namespace peensim {

namespace {

struct GaussNode {
    double x, w;  // -, on [0, 1]
};

// Gauss-Legendre on [0, 1]: 4 points integrate a polynomial of degree 7 exactly, 8 of degree 15.
constexpr GaussNode kGauss4[4] = {{0.069431844202973714, 0.17392742256872687},
                                  {0.33000947820757187, 0.32607257743127305},
                                  {0.66999052179242813, 0.32607257743127305},
                                  {0.93056815579702623, 0.17392742256872687}};
constexpr GaussNode kGauss8[8] = {{0.019855071751231856, 0.050614268145188088}, {0.10166676129318658, 0.11119051722668723},
                                  {0.2372337950418355, 0.15685332293894369},    {0.40828267875217511, 0.181341891689181},
                                  {0.59171732124782495, 0.181341891689181},     {0.7627662049581645, 0.15685332293894369},
                                  {0.89833323870681348, 0.11119051722668723},   {0.9801449282487682, 0.050614268145188088}};

// An end of a piece where the overlap is below this share of the piece's largest is "thin": the
// force there behaves like a power of the distance to a root (delta^3/2, its damping delta^1/4),
// which plain Gauss integrates to a few digits only. Mapping s = end + L w^4 over the part of the
// piece next to it (kMappedShare of it) turns delta^3/2 ds into a polynomial in w and delta^1/4 ds
// into a smooth function; plain Gauss takes the rest.
constexpr double kThinShare = 0.25;
constexpr double kMappedShare = 0.25;
// A piece whose smallest overlap is at least this share of its largest (deep in a contact: the
// roots of the overlap, where the force is singular, at least a piece's length away) takes 4
// Gauss points; others 8.
constexpr double kDeepShare = 0.5;
// A contact whose overlap at the node is more than this many times what its quadratic Taylor
// polynomial moves in the half step stays in contact (the path's other terms are of the third
// order in the step); nearer, its roots are looked for.
constexpr double kReach = 1.25;
// The samples of the overlap over a half step that may hold a root (where it changes sign); a
// contact that begins and ends between two of them (its whole overlap shorter than 1/8 of a step)
// is missed.
constexpr int kRootSamples = 8;
// Below this |rate tau| / delta the twice-integrated force is taken from its Taylor series (the
// closed form would lose digits to cancellation); the series' error there is ~1e-9 of it.
constexpr double kTaylorBelow = 1e-3;

// Roots in (0, H) of c0 + c1 s + c2 s^2, ascending; returns how many (0, 1 or 2).
int quadratic_roots_within(double c0, double c1, double c2, double H, double out[2]) {
    int n = 0;
    const auto keep = [&](double s) {
        if (s > 0.0 && s < H) out[n++] = s;
    };
    if (c2 == 0.0) {
        if (c1 != 0.0) keep(-c0 / c1);
        return n;
    }
    const double disc = c1 * c1 - 4.0 * c2 * c0;
    if (disc < 0.0) return 0;
    // The stable pair of formulas (no cancellation between c1 and the root).
    const double h = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
    if (h == 0.0) return 0;  // c1 = c0 = 0: a double root at 0, not inside
    const double r1 = h / c2, r2 = c0 / h;
    keep(std::min(r1, r2));
    if (r1 != r2) keep(std::max(r1, r2));
    return n;
}

// Whether the path may overlap within the half step to tau = h (s).
bool may_touch(const ContactPath& path, double h_s) {
    const double H = std::abs(h_s);
    if (!(H > 0.0)) return false;
    if (path.overlap_m > 0.0) return true;
    // A gap: until it closes the path is the free motion's parabola q(s), exactly; if that stays
    // apart over the half step (its largest value there, at s = H or at its vertex, is not
    // positive), so does the path.
    const double c0 = path.overlap_m, c1 = (h_s < 0.0 ? -1.0 : 1.0) * path.rate_m_per_s, c2 = 0.5 * path.outer_accel_m_per_s2;
    if (c0 + H * (c1 + H * c2) > 0.0) return true;
    if (!(c2 < 0.0)) return false;
    const double vertex = -c1 / (2.0 * c2);
    return vertex > 0.0 && vertex < H && c0 + vertex * (c1 + vertex * c2) > 0.0;
}

}  // namespace

NodePath::NodePath(const contact::SoftPair& pair, const ContactPath& path, double h_max_s)
    : normal_(path.normal),
      turn_(path.turn_per_s),
      c_(contact::soft_force_shape(pair)),
      hertz_(c_.elastic_power == 1.5 && c_.damping_power == 0.25),
      m_(pair.m_star_kg),
      d0_(path.overlap_m),
      r_(path.rate_m_per_s),
      A_(path.outer_accel_m_per_s2) {
    const double inv_m = 1.0 / m_;
    if (!hertz_) {
        // Other powers: also at an exact touch closing (d0 = 0, r > 0), where a force whose damping
        // has the power 0 (the linear law's) is already c r, and its feedback on the path counts
        // from the first instant (Hertz's is 0 there, its derivatives singular).
        if (d0_ > 0.0 || (d0_ == 0.0 && r_ > 0.0)) general_node(h_max_s);
    } else if (d0_ > 0.0) {
        const double root = std::sqrt(d0_), q = std::sqrt(root), inv_d0 = 1.0 / d0_;
        const double e = c_.elastic * d0_ * root, d = c_.damping * r_ * q;  // N: the force's two terms
        f0_ = e + d;
        f1_ = inv_d0 * (1.5 * e + 0.25 * d);
        f2_ = inv_d0 * inv_d0 * (0.75 * e - 0.1875 * d);
        // The force's own change of speed acting back on it: what the true motion's third
        // and fourth derivatives at the node have beyond the straight path's.
        const double d2 = A_ - f0_ * inv_m;                             // m/s2
        const double f_v = c_.damping * q, f_dv = 0.25 * inv_d0 * f_v;  // dF/d rate, d2F/d delta d rate
        const double d3 = -(f1_ * r_ + f_v * d2) * inv_m;               // m/s3
        c3_ = -f_v * d2 * inv_m;
        // The damping's share of the fourth derivative grows as delta^-1/2 near a root, where
        // the series means nothing (the force is not a smooth function of the time across
        // it): only where the straight path stays in contact over the half step. The elastic
        // share vanishes there by itself.
        c4_ = (d0_ > std::abs(r_) * h_max_s ? -(2.0 * f_dv * r_ * d2 + f1_ * d2 + f_v * d3) : -1.5 * inv_d0 * e * d2) * inv_m;
        phi1_0_ = e * (d0_ * (1.0 / 2.5)) + d * (d0_ * (1.0 / 1.25));
        phi2_0_ = d0_ * d0_ * (e * (1.0 / 8.75) + d * (1.0 / 2.8125));
    }
    // The inner loop multiplies: G / m* = (phi2(x) - phi2(d0) - phi1(d0) r tau) / (r^2 m*).
    if (r_ != 0.0) {
        g_scale_ = 1.0 / (r_ * r_ * m_);
        dg_scale_ = 1.0 / (r_ * m_);
    }
    f0_m_ = f0_ * inv_m, f1_m_ = f1_ * inv_m, f2_m_ = f2_ * inv_m;
    reach_s_ = h_max_s;
    // at(0) is d0 to the bit wherever the terms it multiplies by 0 are finite (as they are but in
    // a state already gone wrong): the half steps then read the node's overlap instead of
    // evaluating it, up to three times each.
    node_overlap_exact_ = std::isfinite(r_ + A_ + c3_ + c4_ + f0_m_ + f1_m_ + f2_m_ + g_scale_ + phi1_0_ + phi2_0_);
}

void NodePath::phis(double x, double& phi1, double& phi2) const {
    if (!(x > 0.0)) {
        phi1 = phi2 = 0.0;
        return;
    }
    if (!hertz_) {
        general_phis(x, phi1, phi2);
        return;
    }
    const double root = std::sqrt(x), q = std::sqrt(root);
    const double e = c_.elastic * x * x * root, d = c_.damping * r_ * x * q;
    phi1 = e * (1.0 / 2.5) + d * (1.0 / 1.25);
    phi2 = x * (e * (1.0 / 8.75) + d * (1.0 / 2.8125));
}

// The node's terms for any powers a (elastic) and b (damping): F = k x^a + c r x^b along the
// straight path, its x-derivatives, and the twice-integrated force at d0 (the Hertz branch above
// is the same with a = 3/2, b = 1/4, written with square roots).
void NodePath::general_node(double h_max_s) {
    const double a = c_.elastic_power, b = c_.damping_power, inv_m = 1.0 / m_;
    // coef x^p, 0 for a zero coefficient (x^p may be infinite at x = 0 where it does not matter).
    const auto term = [&](double coef, double p) { return coef == 0.0 ? 0.0 : coef * std::pow(d0_, p); };
    const double k = c_.elastic, cr = c_.damping * r_;
    const double e = term(k, a), d = term(cr, b);  // N: the force's two terms
    f0_ = e + d;
    const double f1_elastic = term(a * k, a - 1.0);
    f1_ = f1_elastic + term(b * cr, b - 1.0);
    f2_ = term(a * (a - 1.0) * k, a - 2.0) + term(b * (b - 1.0) * cr, b - 2.0);
    const double d2 = A_ - f0_ * inv_m;
    const double f_v = term(c_.damping, b), f_dv = term(b * c_.damping, b - 1.0);  // dF/d rate, d2F/d delta d rate
    const double d3 = -(f1_ * r_ + f_v * d2) * inv_m;
    c3_ = -f_v * d2 * inv_m;
    // As Hertz's: where the straight path may leave the contact within the half step, only the
    // elastic share (the series means nothing across the root).
    c4_ = (d0_ > std::abs(r_) * h_max_s ? -(2.0 * f_dv * r_ * d2 + f1_ * d2 + f_v * d3) : -f1_elastic * d2) * inv_m;
    phi1_0_ = e * d0_ / (a + 1.0) + d * d0_ / (b + 1.0);
    phi2_0_ = d0_ * d0_ * (e / ((a + 1.0) * (a + 2.0)) + d / ((b + 1.0) * (b + 2.0)));
    if (!std::isfinite(f0_ + f1_ + f2_ + c3_ + c4_)) f0_ = f1_ = f2_ = c3_ = c4_ = 0.0;  // singular at the root: as Hertz's
}

void NodePath::general_phis(double x, double& phi1, double& phi2) const {
    const double a = c_.elastic_power, b = c_.damping_power;
    const double e = c_.elastic * std::pow(x, a + 1.0), d = c_.damping * r_ * std::pow(x, b + 1.0);
    phi1 = e / (a + 1.0) + d / (b + 1.0);
    phi2 = x * (e / ((a + 1.0) * (a + 2.0)) + d / ((b + 1.0) * (b + 2.0)));
}

double NodePath::general_force(double delta, double rate) const {
    if (!(delta > 0.0)) return 0.0;  // apart (a damping power of 0 would otherwise pull at a gap)
    return c_.elastic * std::pow(delta, c_.elastic_power) + c_.damping * std::pow(delta, c_.damping_power) * rate;
}

void NodePath::at(const double* tau, int n, double* delta, double* rate) const {
    double x[kMaxPoints], root[kMaxPoints], q[kMaxPoints];
    for (int i = 0; i < n; ++i) x[i] = std::max(0.0, d0_ + r_ * tau[i]);
    for (int i = 0; i < n; ++i) root[i] = std::sqrt(x[i]);
    for (int i = 0; i < n; ++i) q[i] = std::sqrt(root[i]);
    for (int i = 0; i < n; ++i) {
        double p1 = 0.0, p2 = 0.0;
        if (hertz_) {
            const double e = c_.elastic * x[i] * x[i] * root[i], d = c_.damping * r_ * x[i] * q[i];
            p1 = e * (1.0 / 2.5) + d * (1.0 / 1.25), p2 = x[i] * (e * (1.0 / 8.75) + d * (1.0 / 2.8125));
        } else if (x[i] > 0.0) {
            general_phis(x[i], p1, p2);
        }
        const double t = tau[i], t2 = t * t;
        const double G = (p2 - phi2_0_ - phi1_0_ * r_ * t) * g_scale_, dG = (p1 - phi1_0_) * dg_scale_;
        delta[i] = d0_ + t * (r_ + 0.5 * A_ * t) - G + t2 * t * (c3_ * (1.0 / 6.0) + c4_ * t * (1.0 / 24.0));
        rate[i] = r_ + A_ * t - dG + t2 * (0.5 * c3_ + c4_ * t * (1.0 / 6.0));
    }
    if (!(d0_ > 0.0)) return;
    for (int i = 0; i < n; ++i)
        if (!(std::abs(r_ * tau[i]) > kTaylorBelow * d0_)) at(tau[i], delta[i], rate[i]);
}

void NodePath::at(double tau, double& delta, double& rate) const {
    double G = 0.0, dG = 0.0;  // m, m/s: the own force integrated twice and once, over m*
    if (d0_ > 0.0 && !(std::abs(r_ * tau) > kTaylorBelow * d0_)) {
        const double rt = r_ * tau;
        G = tau * tau * (0.5 * f0_m_ + rt * (f1_m_ * (1.0 / 6.0) + rt * f2_m_ * (1.0 / 24.0)));
        dG = tau * (f0_m_ + rt * (0.5 * f1_m_ + rt * f2_m_ * (1.0 / 6.0)));
    } else if (r_ != 0.0) {
        double p1 = 0.0, p2 = 0.0;
        phis(d0_ + r_ * tau, p1, p2);
        G = (p2 - phi2_0_ - phi1_0_ * r_ * tau) * g_scale_;
        dG = (p1 - phi1_0_) * dg_scale_;
    }
    const double t2 = tau * tau;
    delta = d0_ + tau * (r_ + 0.5 * A_ * tau) - G + t2 * tau * (c3_ * (1.0 / 6.0) + c4_ * tau * (1.0 / 24.0));
    rate = r_ + A_ * tau - dG + t2 * (0.5 * c3_ + c4_ * tau * (1.0 / 6.0));
}

HalfStepImpulse NodePath::half_step(double h_s) const {
    HalfStepImpulse out;
    // An empty path, or a gap that stays open over this half step.
    if (!(reach_s_ > 0.0) || !may_touch({d0_, r_, A_, normal_, turn_}, h_s)) return out;
    const double H = std::abs(h_s);
    const double sign = h_s < 0.0 ? -1.0 : 1.0;
    const auto overlap = [&](double s) {
        if (s == 0.0 && node_overlap_exact_) return d0_;
        double d, r;
        at(sign * s, d, r);
        return d;
    };
    // The quadrature's points (s) and weights (s), gathered first, evaluated together at the end.
    double qs[kMaxPoints], qw[kMaxPoints];
    int points = 0;
    const auto add = [&](double s, double weight) {
        qs[points] = s;
        qw[points++] = weight;
    };
    // Gauss on [a, b], mapped to cluster at a thin end (-1: a, +1: b, 0: neither; 2: neither, deep).
    const auto piece = [&](double a, double b, int thin) {
        const double L = b - a;
        if (!(L > 0.0)) return;
        if (thin == 2) {
            for (const GaussNode& g : kGauss4) add(a + g.x * L, g.w * L);
            return;
        }
        for (const GaussNode& g : kGauss8) {
            if (thin == 0) {
                add(a + g.x * L, g.w * L);
            } else {
                const double w2 = g.x * g.x;
                const double jacobian = 4.0 * L * w2 * g.x;  // ds/dw of s = end +- L w^4
                add(thin < 0 ? a + L * w2 * w2 : b - L * w2 * w2, g.w * jacobian);
            }
        }
    };
    const auto thin_piece = [&](double a, double b, int thin) {
        if (thin < 0) {
            const double m = a + kMappedShare * (b - a);
            piece(a, m, -1);
            piece(m, b, 0);
        } else {
            const double m = b - kMappedShare * (b - a);
            piece(a, m, 0);
            piece(m, b, +1);
        }
    };
    // The roots: where a deep contact cannot reach zero within the half step (kReach times its
    // Taylor excursion), none. Else the roots of the path's quadratic Taylor polynomial (exact before a
    // contact begins: the force is nil there) are found in closed form and each refined on the
    // path by Newton's iteration within a bracket around it; should a bracket not be found there
    // (the polynomial too far off), the sign changes of kRootSamples samples instead.
    double cuts[kRootSamples + 2];
    int n = 0;
    cuts[n++] = 0.0;
    const double total_accel = A_ - f0_ / m_;
    // s (> lo, < hi) where the path is zero, its overlap d_lo at lo and d_hi at hi of opposite signs.
    const auto refine = [&](double lo, double hi, double d_lo, double d_hi) {
        double s = lo + (hi - lo) * d_lo / (d_lo - d_hi);  // secant
        for (int it = 0; it < 60; ++it) {
            double d, r;
            at(sign * s, d, r);
            if (d == 0.0) break;
            ((d > 0.0) == (d_lo > 0.0) ? lo : hi) = s;
            const double slope = sign * r;  // d delta / ds
            double next = slope != 0.0 ? s - d / slope : 0.5 * (lo + hi);
            if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
            const bool done = std::abs(next - s) <= 1e-15 * H;
            s = next;
            if (done) break;
        }
        return s;
    };
    if (!(d0_ > kReach * (std::abs(r_) * H + 0.5 * std::abs(total_accel) * H * H))) {
        double guesses[2];
        const int g = quadratic_roots_within(d0_, sign * r_, 0.5 * total_accel, H, guesses);
        bool bracketed = true;
        for (int k = 0; k < g && bracketed; ++k) {
            bracketed = false;
            for (double w = 1e-3 * H; w < 0.3 * H && !bracketed; w *= 8.0) {
                const double lo = std::max(cuts[n - 1], guesses[k] - w), hi = std::min(H, guesses[k] + w);
                const double d_lo = overlap(lo), d_hi = overlap(hi);
                if ((d_lo > 0.0) == (d_hi > 0.0)) continue;
                cuts[n++] = refine(lo, hi, d_lo, d_hi);
                bracketed = true;
            }
        }
        if (!bracketed) {
            n = 1;
            double s0 = 0.0, d_lo = overlap(0.0);
            for (int k = 1; k <= kRootSamples; ++k) {
                const double s1 = H * k / kRootSamples, d_hi = overlap(s1);
                if ((d_lo > 0.0) != (d_hi > 0.0)) cuts[n++] = refine(s0, s1, d_lo, d_hi);
                s0 = s1;
                d_lo = d_hi;
            }
        }
    }
    cuts[n++] = H;
    for (int k = 0; k + 1 < n; ++k) {
        const double a = cuts[k], b = cuts[k + 1], mid = 0.5 * (a + b);
        // The sign is the same all along a piece (its ends are the roots): an overlap or a gap.
        const double d_mid = overlap(mid);
        if (!(d_mid > 0.0)) continue;
        const double d_a = overlap(a), d_b = overlap(b), top = std::max({d_a, d_b, d_mid});
        const bool thin_a = !(d_a > kThinShare * top), thin_b = !(d_b > kThinShare * top);
        if (thin_a && thin_b) {
            thin_piece(a, mid, -1);
            thin_piece(mid, b, +1);
        } else if (thin_a || thin_b) {
            thin_piece(a, b, thin_a ? -1 : +1);
        } else {
            piece(a, b, std::min(d_a, d_b) >= kDeepShare * top ? 2 : 0);
        }
    }
    // The weighted force at every point, both ways.
    double tau[kMaxPoints], delta[kMaxPoints], rate[kMaxPoints], f[kMaxPoints];
    for (int i = 0; i < points; ++i) tau[i] = sign * qs[i];
    at(tau, points, delta, rate);
    const contact::SoftForceShape& c = c_;
    if (!hertz_) {
        for (int i = 0; i < points; ++i) f[i] = qw[i] * general_force(delta[i], rate[i]);
    } else if (c.damping == 0.0) {
        for (int i = 0; i < points; ++i) {
            const double d = std::max(0.0, delta[i]);
            f[i] = qw[i] * c.elastic * d * std::sqrt(d);
        }
    } else {
        for (int i = 0; i < points; ++i) {
            const double d = std::max(0.0, delta[i]), root = std::sqrt(d);
            f[i] = qw[i] * (c.elastic * d * root + c.damping * std::sqrt(root) * rate[i]);
        }
    }
    double near = 0.0, far = 0.0;  // N s
    if (turn_ == Vec3::Zero()) {
        for (int i = 0; i < points; ++i) {
            near += (1.0 - qs[i] / H) * f[i];
            far += (qs[i] / H) * f[i];
        }
        out.near = near * normal_;
        out.far = far * normal_;
        return out;
    }
    for (int i = 0; i < points; ++i) {
        const Vec3 n = (normal_ + tau[i] * turn_).normalized();
        out.near += ((1.0 - qs[i] / H) * f[i]) * n;
        out.far += ((qs[i] / H) * f[i]) * n;
    }
    return out;
}

HalfStepImpulse half_step_impulse(const contact::SoftPair& pair, const ContactPath& path, double h_s) {
    if (!may_touch(path, h_s)) return {};
    return NodePath(pair, path, std::abs(h_s)).half_step(h_s);
}

NodePath node_path(const contact::SoftPair& pair, const ContactPath& path, double h_before_s, double h_after_s) {
    if (!may_touch(path, -h_before_s) && !may_touch(path, h_after_s)) return NodePath();
    return NodePath(pair, path, std::max(h_before_s, h_after_s));
}

void contact_path_at(const contact::SoftPair& pair, const ContactPath& path, double h_s, double tau_s, double& overlap_m,
                     double& rate_m_per_s) {
    NodePath(pair, path, std::abs(h_s)).at(tau_s, overlap_m, rate_m_per_s);
}

}  // namespace peensim
