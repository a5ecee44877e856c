#include "kernels/sphere_triangle_toi.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/float_limits.h"
#include "kernels/polynomial_roots.h"

namespace peensim {

namespace {

// Culls reject a feature only when it is clear by more than this fraction of the radius, far
// above the rounding of the distances they compare.
constexpr double kCullSlack = 1e-9;

bool entering(RootKind kind) { return kind == RootKind::falling || kind == RootKind::touch_from_above; }

// |A + B u + C u^2|^2 - r2: the squared distance to a point (A, B, C the relative position's
// coefficients) or, with A, B, C crossed with an edge, |e|^2 times the squared distance to its line.
Polynomial gap_polynomial(const Vec3& A, const Vec3& B, const Vec3& C, double r2) {
    Polynomial p;
    p.degree = 4;
    p.c = {A.dot(A) - r2, 2.0 * A.dot(B), B.dot(B) + 2.0 * A.dot(C), 2.0 * B.dot(C), C.dot(C)};
    return p;
}

TriangleFeature edge_feature(int k) {
    return k == 0 ? TriangleFeature::edge_ab : (k == 1 ? TriangleFeature::edge_bc : TriangleFeature::edge_ca);
}
TriangleFeature vertex_feature(int k) {
    return k == 0 ? TriangleFeature::vertex_a : (k == 1 ? TriangleFeature::vertex_b : TriangleFeature::vertex_c);
}

// The centre as u = t - t_from: P + V u + H u^2 (H = g / 2).
struct LocalPath {
    Vec3 P, V, H;
    Vec3 at(double u) const { return P + u * (V + u * H); }
    // How far the centre can be, over [lo, hi], from its position at the middle (returned in
    // `mid`): |v(mid)| half + |g| half^2 / 2 bounds |p(u) - p(mid)| exactly.
    double reach(double lo, double hi, Vec3& mid) const {
        const double um = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
        mid = at(um);
        return (V + 2.0 * um * H).norm() * half + H.norm() * half * half;
    }
};

void bounding_sphere(const Vec3& a, const Vec3& b, const Vec3& c, Vec3& centre, double& radius) {
    centre = (a + b + c) / 3.0;
    radius = std::sqrt(std::max({(a - centre).squaredNorm(), (b - centre).squaredNorm(), (c - centre).squaredNorm()}));
}

}  // namespace

bool sphere_triangle_first_touch(const Trajectory& path, double radius, const Vec3& a, const Vec3& b, const Vec3& c, double t_from,
                                 double t_to, TriangleContact& out) {
    if (!(t_to >= t_from)) return false;
    const double R = radius;
    const double slack = kCullSlack * R;
    const LocalPath path_u{path.position(t_from), path.velocity(t_from), 0.5 * path.g};
    const Vec3 corner[3] = {a, b, c};
    double lo = 0.0, hi = t_to - t_from;

    // The cheap cull: distance to the triangle's bounding sphere less the travel over the window.
    {
        Vec3 centre, mid;
        double rho;
        bounding_sphere(a, b, c, centre, rho);
        const double reach = path_u.reach(lo, hi, mid);
        if ((mid - centre).norm() > rho + reach + R + slack) return false;
    }

    bool found = false;
    auto take = [&](double u, const Vec3& point, const Vec3& normal, TriangleFeature feature) {
        found = true;
        hi = u;  // later candidates must beat this one
        out.time = t_from + u;
        out.point = point;
        out.normal = normal;
        out.feature = feature;
    };

    Vec3 n = (b - a).cross(c - a);
    const double n_len = n.norm();
    if (n_len > 0.0) {
        n /= n_len;
        // Signed distance to the plane s(u) = s0 + s1 u + s2 u^2; the sphere is in the slab
        // |s| <= R whenever it can touch the triangle at all.
        const Vec3 q0 = path_u.P - a;
        const double s0 = n.dot(q0), s1 = n.dot(path_u.V), s2 = n.dot(path_u.H);
        Polynomial above, below;  // gaps to the slab's faces, positive outside it
        above.degree = below.degree = 2;
        above.c = {s0 - R, s1, s2, 0.0, 0.0};
        below.c = {-s0 - R, -s1, -s2, 0.0, 0.0};
        PolynomialRoots roots_above, roots_below;
        real_roots_in(above, lo, hi, roots_above);
        real_roots_in(below, lo, hi, roots_below);

        const Vec3 e0 = b - a, e1 = c - b, e2 = a - c;
        const Vec3 b_rel = b - a, c_rel = c - a;
        auto inside = [&](const Vec3& foot) {  // foot relative to a, in the plane
            return e0.cross(foot).dot(n) >= 0.0 && e1.cross(foot - b_rel).dot(n) >= 0.0 && e2.cross(foot - c_rel).dot(n) >= 0.0;
        };
        // Face contacts: entering the slab with the foot inside. A first entry with the foot
        // outside may be followed by a second one (the parabola leaves and comes back).
        auto face = [&](const PolynomialRoots& roots, double side) {
            for (int i = 0; i < roots.count; ++i) {
                const PolynomialRoot& r = roots.root[static_cast<std::size_t>(i)];
                if (r.t > hi || (found && r.t >= hi)) return;
                if (!entering(r.kind)) continue;
                const Vec3 q = path_u.at(r.t) - a;
                const Vec3 foot = q - n.dot(q) * n;
                if (inside(foot)) {
                    take(r.t, a + foot, side * n, TriangleFeature::face);
                    return;
                }
            }
        };
        face(roots_above, 1.0);
        face(roots_below, -1.0);

        // The slab window [first, last] bounds every edge and vertex contact too.
        auto s_at = [&](double u) { return s0 + u * (s1 + u * s2); };
        const double s_lo = s_at(lo), s_hi = s_at(hi);
        double first = lo, last = hi;
        if (s_lo > R || s_lo < -R) {
            const PolynomialRoots& r = s_lo > R ? roots_above : roots_below;
            if (r.count == 0) return found;
            first = r.root[0].t;
        }
        if (s_hi > R || s_hi < -R) {
            const PolynomialRoots& r = s_hi > R ? roots_above : roots_below;
            if (r.count == 0) return found;
            last = r.root[static_cast<std::size_t>(r.count - 1)].t;
        }
        // A contact at an edge exactly where the slab is entered is one root of two polynomials:
        // keep a few ulps either side so it cannot fall out of the window.
        const double widen = 4.0 * kEps * hi;
        lo = std::max(lo, first - widen);
        hi = std::min(hi, last + widen);
    }

    for (int k = 0; k < 3 && lo <= hi; ++k) {
        const Vec3& o = corner[k];
        const Vec3 e = corner[(k + 1) % 3] - o;
        const double ee = e.squaredNorm();
        if (ee == 0.0) continue;  // a degenerate edge: its vertices stand for it
        Vec3 mid;
        const double reach = path_u.reach(lo, hi, mid);
        const Vec3 m = mid - o;
        const double lam_mid = std::clamp(m.dot(e) / ee, 0.0, 1.0);
        if ((m - lam_mid * e).norm() > R + reach + slack) continue;
        const Vec3 q0 = path_u.P - o;
        const Polynomial gap = gap_polynomial(q0.cross(e), path_u.V.cross(e), path_u.H.cross(e), R * R * ee);
        PolynomialRoots roots;
        real_roots_in(gap, lo, hi, roots);
        for (int i = 0; i < roots.count; ++i) {
            const PolynomialRoot& r = roots.root[static_cast<std::size_t>(i)];
            if (found && r.t >= hi) break;
            if (!entering(r.kind)) continue;
            const Vec3 centre = path_u.at(r.t);
            const double lam = (centre - o).dot(e) / ee;
            if (lam < 0.0 || lam > 1.0) continue;
            const Vec3 foot = o + lam * e;
            take(r.t, foot, (centre - foot).normalized(), edge_feature(k));
            break;
        }
    }

    for (int k = 0; k < 3 && lo <= hi; ++k) {
        const Vec3& o = corner[k];
        Vec3 mid;
        const double reach = path_u.reach(lo, hi, mid);
        if ((mid - o).norm() > R + reach + slack) continue;
        const Polynomial gap = gap_polynomial(path_u.P - o, path_u.V, path_u.H, R * R);
        PolynomialRoot r;
        if (!first_root_in(gap, lo, hi, r, RootFilter::entering)) continue;
        if (found && r.t >= hi) continue;
        take(r.t, o, (path_u.at(r.t) - o).normalized(), vertex_feature(k));
    }
    return found;
}

ToiStatus sphere_triangle_toi(const Trajectory& path, double radius, const Vec3& a, const Vec3& b, const Vec3& c, double t_begin,
                              double t_end, TriangleContact& out) {
    if (!(t_end >= t_begin)) return ToiStatus::miss;
    const Vec3 P = path.position(t_begin);
    Vec3 centre;
    double rho;
    bounding_sphere(a, b, c, centre, rho);
    if ((P - centre).norm() < rho + radius) {
        const ClosestPoint closest = closest_point_on_triangle(P, a, b, c);
        const Vec3 d = P - closest.point;
        const double dist = d.norm();
        // A gap within +-kStartTouchFraction R is a touch, decided by the approach sign alone: the
        // feature polynomials cannot tell a zero gap from one of the sign of their rounding
        // (their constant terms are differences of millimetre-sized numbers).
        if (dist < radius * (1.0 + kStartTouchFraction)) {
            Vec3 normal = (b - a).cross(c - a);
            if (dist > 0.0)
                normal = d / dist;
            else
                normal = normal.norm() > 0.0 ? Vec3(normal.normalized()) : Vec3(Vec3::UnitZ());
            out.time = t_begin;
            out.point = closest.point;
            out.normal = normal;
            out.feature = closest.feature;
            if (dist < radius * (1.0 - kStartTouchFraction)) return ToiStatus::overlapping;
            // Touching: an impact now if approaching (or at rest and pulled in); separating, as
            // right after a bounce, the search below discards the roots where it leaves.
            const double rate = normal.dot(path.velocity(t_begin));
            if (rate < 0.0 || (rate == 0.0 && normal.dot(path.g) < 0.0)) return ToiStatus::impact;
        }
    }
    return sphere_triangle_first_touch(path, radius, a, b, c, t_begin, t_end, out) ? ToiStatus::impact : ToiStatus::miss;
}

}  // namespace peensim
