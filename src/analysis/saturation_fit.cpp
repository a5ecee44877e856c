#include "analysis/saturation_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "analysis/student_t.h"
#include "common/float_limits.h"

namespace peensim {

namespace {

// The profile grid the fits start from, in the scaled units below (exposures / the longest, so
// b' = b t_max^c): ln b' from ln 1e-4 (the longest strip at 0.01 % of the plateau: a straight line)
// to ln 1e5 (the shortest at the plateau), and the 3P shape c over 0.1 .. 8.
constexpr double kLogBLow = -9.210340371976184;   // ln 1e-4
constexpr double kLogBHigh = 11.512925464970229;  // ln 1e5
constexpr int kLogBSteps = 460;
constexpr double kShapeLow = 0.1, kShapeHigh = 8.0;
constexpr int kShapeSteps = 48;
// Beyond these the data do not pin the curve down: the longest exposure below 5 % of the plateau
// (no knee yet), or the shortest within exp(-15) = 3e-7 of it (all strips already saturated: any
// steeper curve fits as well), or a 3P shape outside 0.05 .. 20.
constexpr double kNoKneeExposure = 0.05, kAllSaturatedExposure = 15.0;
constexpr double kShapeMin = 0.05, kShapeMax = 20.0;
// A 2P fit whose RMS residual is below this share of its plateau fits to rounding: the F-test would
// only compare rounding errors.
constexpr double kExactFit = 1e-9;

// The data scaled to order one (exposure / longest, height / highest): the fit's numbers then do
// not depend on the units (s or min, mm or thou). Replicates are merged: one point per distinct
// exposure, its height the replicates' mean and its weight their count. The least squares are the
// same (each replicate's squared residual is its group's plus its distance to the group mean,
// which no curve changes: `within`), at a cost that grows with the distinct exposures, not the
// rows.
struct Scaled {
    std::vector<double> t, log_t, h, w;  // t' in [0, 1], ln t' (unused where t' = 0), mean h' in [0, 1], replicates
    double within = 0.0;                 // sum of the replicates' squared distances to their group mean (h' units^2)
    double t_scale = 1.0, h_scale = 1.0;
};

// Parameters in scaled units: q = (A, beta, c), h' = A (1 - exp(-exp(beta) t'^c)).
using Params = Eigen::Vector3d;

// exp(beta) t'^c, the exponent at one point (0 at t' = 0).
double exponent_at(const Scaled& s, std::size_t i, double beta, double c) { return s.t[i] > 0.0 ? std::exp(beta + c * s.log_t[i]) : 0.0; }

// The weighted sum over the groups (the replicates' `within` not included).
double sum_of_squares(const Scaled& s, const Params& q) {
    double ssr = 0.0;
    for (std::size_t i = 0; i < s.t.size(); ++i) {
        const double r = q[0] * -std::expm1(-exponent_at(s, i, q[1], q[2])) - s.h[i];
        ssr += s.w[i] * r * r;
    }
    return ssr;
}

// For given beta and c, the best A (linear least squares) and the residual sum of squares (up to
// the constant `within`).
std::pair<double, double> profile(const Scaled& s, double beta, double c) {
    double ff = 0.0, fh = 0.0, hh = 0.0;
    for (std::size_t i = 0; i < s.t.size(); ++i) {
        const double f = -std::expm1(-exponent_at(s, i, beta, c));
        ff += s.w[i] * f * f;
        fh += s.w[i] * f * s.h[i];
        hh += s.w[i] * s.h[i] * s.h[i];
    }
    if (!(ff > 0.0)) return {0.0, hh};
    return {fh / ff, hh - fh * fh / ff};
}

// At most this many points are profiled on the start grid (48 x 461 curves): more distinct
// exposures are merged, neighbours in exposure, into this many for the start only (the fit itself
// runs on them all). A start needs the curve's shape, not every strip: with 10^4 distinct exposures
// the grid alone took 4 s, growing with the rows.
constexpr std::size_t kStartPoints = 256;

Scaled start_points(const Scaled& s) {
    if (s.t.size() <= kStartPoints) return s;
    Scaled c;
    c.t_scale = s.t_scale;
    c.h_scale = s.h_scale;
    const std::size_t n = s.t.size();
    for (std::size_t b = 0; b < kStartPoints; ++b) {
        const std::size_t from = b * n / kStartPoints, to = (b + 1) * n / kStartPoints;
        double w = 0.0, t = 0.0, h = 0.0;
        for (std::size_t i = from; i < to; ++i) {
            w += s.w[i];
            t += s.w[i] * s.t[i];
            h += s.w[i] * s.h[i];
        }
        c.t.push_back(t / w);
        c.log_t.push_back(t > 0.0 ? std::log(t / w) : 0.0);
        c.h.push_back(h / w);
        c.w.push_back(w);
    }
    return c;
}

// Residuals and Jacobian (columns A, beta, c; the first `p` used), each group's row weighted by
// the square root of its replicates (so that J^T J and J^T r are those of every row).
void residuals(const Scaled& s, const Params& q, int p, Eigen::VectorXd& r, Eigen::MatrixXd& J) {
    const auto n = static_cast<Eigen::Index>(s.t.size());
    r.resize(n);
    J.resize(n, p);
    for (Eigen::Index i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        const double u = exponent_at(s, k, q[1], q[2]);
        const double e = std::exp(-u);
        const double root_w = std::sqrt(s.w[k]);
        r[i] = root_w * (q[0] * -std::expm1(-u) - s.h[k]);
        J(i, 0) = root_w * -std::expm1(-u);
        J(i, 1) = root_w * q[0] * e * u;
        if (p == 3) J(i, 2) = s.t[k] > 0.0 ? root_w * q[0] * e * u * s.log_t[k] : 0.0;
    }
}

// Levenberg-Marquardt from q on the first p parameters (c stays fixed when p == 2).
Params levenberg_marquardt(const Scaled& s, Params q, int p) {
    Eigen::VectorXd r;
    Eigen::MatrixXd J;
    double lambda = 1e-3;
    double ssr = sum_of_squares(s, q);
    for (int iteration = 0; iteration < 500 && ssr > 0.0; ++iteration) {
        residuals(s, q, p, r, J);
        const Eigen::MatrixXd H = J.transpose() * J;
        const Eigen::VectorXd g = J.transpose() * r;
        bool moved = false;
        Eigen::VectorXd step;
        while (lambda < 1e20) {
            Eigen::MatrixXd M = H;
            for (int j = 0; j < p; ++j) M(j, j) += lambda * std::max(H(j, j), 1e-300);
            step = M.ldlt().solve(-g);
            Params trial = q;
            for (int j = 0; j < p; ++j) trial[j] += step[j];
            const double trial_ssr = (p == 3 && !(trial[2] > 0.0)) ? std::numeric_limits<double>::infinity() : sum_of_squares(s, trial);
            if (trial_ssr <= ssr) {
                q = trial;
                ssr = trial_ssr;
                lambda = std::max(lambda * 0.1, 1e-15);
                moved = true;
                break;
            }
            lambda *= 10.0;
        }
        if (!moved) break;  // no step lowers the residual: at the minimum to rounding
        bool small = true;
        for (int j = 0; j < p; ++j) small = small && std::fabs(step[j]) <= 1e-15 * (1.0 + std::fabs(q[j]));
        if (small) break;
    }
    return q;
}

SaturationCurve physical(const Scaled& s, const Params& q) {
    SaturationCurve c;
    c.a = q[0] * s.h_scale;
    c.c = q[2];
    c.b = std::exp(q[1]) / std::pow(s.t_scale, q[2]);
    return c;
}

std::string text(double v) {
    std::ostringstream o;
    o.precision(3);
    o << v;
    return o.str();
}

}  // namespace

const char* saturation_form_name(SaturationForm form) { return form == SaturationForm::two_parameter ? "2P" : "3P"; }

double SaturationCurve::arc_height(double t) const {
    if (!(t > 0.0)) return 0.0;
    return a * -std::expm1(-b * std::pow(t, c));
}

SaturationPoint saturation_point(const SaturationCurve& curve) {
    SaturationPoint p;
    if (!(curve.a > 0.0) || !(curve.b > 0.0) || !(curve.c > 0.0)) return p;
    double y = 0.0;  // b T^c
    if (curve.c == 1.0) {
        y = std::log(10.0);  // (1 - x^2) / (1 - x) = 1 + x = 1.1: x = exp(-y) = 0.1
    } else {
        const double k = std::exp2(curve.c);
        if (!(k > kSaturationRise)) return p;
        // ratio(y) = (1 - exp(-k y)) / (1 - exp(-y)) falls from k (y -> 0) to 1 (y -> inf): one
        // root, bisected on ln y until the bracket is two adjacent doubles.
        auto ratio = [k](double yy) { return std::expm1(-k * yy) / std::expm1(-yy); };
        double lo = 1e-12, hi = 80.0;
        if (!(ratio(lo) > kSaturationRise)) return p;  // c barely above log2(1.1): T beyond any exposure
        for (int i = 0; i < 400; ++i) {
            const double mid = std::sqrt(lo * hi);
            if (!(mid > lo && mid < hi)) break;
            (ratio(mid) > kSaturationRise ? lo : hi) = mid;
        }
        y = std::fabs(ratio(lo) - kSaturationRise) < std::fabs(ratio(hi) - kSaturationRise) ? lo : hi;
    }
    p.exists = true;
    p.time = std::pow(y / curve.b, 1.0 / curve.c);
    p.intensity = curve.a * -std::expm1(-y);
    return p;
}

ArcHeightFall arc_height_fall(std::span<const SaturationDatum> data) {
    ArcHeightFall f;
    double shortest = 0.0, longest = 0.0, highest = 0.0;
    for (const SaturationDatum& d : data) {
        if (d.exposure > 0.0 && (shortest == 0.0 || d.exposure < shortest)) shortest = d.exposure;
        longest = std::max(longest, d.exposure);
        highest = std::max(highest, std::fabs(d.arc_height));
    }
    if (!(shortest > 0.0) || !(longest > shortest)) return f;
    double at_shortest = 0.0, at_longest = 0.0;
    int n_shortest = 0, n_longest = 0;
    for (const SaturationDatum& d : data) {
        if (d.exposure == shortest) at_shortest += d.arc_height, ++n_shortest;
        if (d.exposure == longest) at_longest += d.arc_height, ++n_longest;
    }
    f.shortest_exposure = shortest;
    f.longest_exposure = longest;
    f.shortest_height = at_shortest / n_shortest;
    f.longest_height = at_longest / n_longest;
    f.falls = f.shortest_height - f.longest_height > kFallingShare * highest;
    return f;
}

SaturationFit fit_saturation_curve(std::span<const SaturationDatum> data, SaturationForm form) {
    SaturationFit fit;
    fit.form = form;
    fit.parameters = form == SaturationForm::two_parameter ? 2 : 3;
    fit.points = static_cast<int>(data.size());
    fit.residual_sd = fit.time_standard_error = fit.intensity_standard_error = kNaN;
    std::set<double> exposures;
    Scaled s;
    // The scales: the longest exposure and the highest arc height.
    s.t_scale = 0.0;
    s.h_scale = 0.0;
    for (const SaturationDatum& d : data) {
        if (d.exposure > 0.0) exposures.insert(d.exposure);
        s.t_scale = std::max(s.t_scale, d.exposure);
        s.h_scale = std::max(s.h_scale, std::fabs(d.arc_height));
    }
    const std::size_t needed = static_cast<std::size_t>(fit.parameters);
    if (exposures.size() < needed) {
        fit.problem = "needs at least " + std::to_string(needed) + " distinct exposures > 0 (has " + std::to_string(exposures.size()) + ")";
        return fit;
    }
    if (!(s.h_scale > 0.0)) {
        fit.problem = "every arc height is zero";
        return fit;
    }
    if (const ArcHeightFall fall = arc_height_fall(data); fall.falls) {
        fit.problem = "the arc heights fall with exposure (" + text(fall.shortest_height) + " at the shortest exposure, " +
                      text(fall.longest_height) + " at the longest): a saturation curve rises, then levels off";
        return fit;
    }
    // One point per distinct exposure (std::map: in increasing exposure), then the replicates'
    // spread about their means.
    std::map<double, std::pair<double, double>> groups;  // exposure -> (replicates, sum of h')
    for (const SaturationDatum& d : data) {
        auto& g = groups[d.exposure];
        g.first += 1.0;
        g.second += d.arc_height / s.h_scale;
    }
    for (const auto& [exposure, g] : groups) {
        s.t.push_back(exposure / s.t_scale);
        s.log_t.push_back(exposure > 0.0 ? std::log(exposure / s.t_scale) : 0.0);
        s.h.push_back(g.second / g.first);
        s.w.push_back(g.first);
    }
    for (const SaturationDatum& d : data) {
        const auto& g = groups[d.exposure];
        const double r = d.arc_height / s.h_scale - g.second / g.first;
        s.within += r * r;
    }

    // Start: the best point of the profile grid.
    Params q(0.0, 0.0, 1.0);
    double best = std::numeric_limits<double>::infinity();
    const int shapes = form == SaturationForm::two_parameter ? 1 : kShapeSteps;
    const Scaled start = start_points(s);
    for (int ic = 0; ic < shapes; ++ic) {
        const double c = shapes == 1 ? 1.0 : kShapeLow * std::pow(kShapeHigh / kShapeLow, ic / (shapes - 1.0));
        for (int ib = 0; ib <= kLogBSteps; ++ib) {
            const double beta = kLogBLow + (kLogBHigh - kLogBLow) * ib / kLogBSteps;
            const auto [A, ssr] = profile(start, beta, c);
            if (A > 0.0 && ssr < best) {
                best = ssr;
                q = Params(A, beta, c);
            }
        }
    }
    if (!std::isfinite(best)) {
        fit.problem = "no rising curve fits the data (the arc heights do not increase with exposure)";
        return fit;
    }
    q = levenberg_marquardt(s, q, fit.parameters);

    fit.curve = physical(s, q);
    fit.residual_sum_of_squares = (sum_of_squares(s, q) + s.within) * s.h_scale * s.h_scale;
    fit.rms_residual = std::sqrt(fit.residual_sum_of_squares / fit.points);
    const int dof = fit.points - fit.parameters;
    if (dof > 0) fit.residual_sd = std::sqrt(fit.residual_sum_of_squares / dof);
    fit.point = saturation_point(fit.curve);
    fit.fitted = true;

    // Whether the data pin the curve down.
    const double t_min = *exposures.begin() / s.t_scale;
    const double u_longest = std::exp(q[1]), u_shortest = std::exp(q[1] + q[2] * std::log(t_min));
    if (!(q[0] > 0.0)) {
        fit.problem = "the fitted curve does not rise";
        fit.fitted = false;
    } else if (u_longest < kNoKneeExposure) {
        fit.problem = "the arc heights do not level off within the measured exposures (no knee in the data): peen strips longer";
        fit.fitted = false;
    } else if (u_shortest > kAllSaturatedExposure) {
        fit.problem = "every strip is already at the plateau (the knee lies before the shortest exposure): peen strips shorter";
        fit.fitted = false;
    } else if (fit.parameters == 3 && (q[2] < kShapeMin || q[2] > kShapeMax)) {
        fit.problem = "the 3P shape c = " + text(q[2]) + " is not determined by the data";
        fit.fitted = false;
    } else if (!fit.point.exists) {
        fit.problem = "the fitted curve (c = " + text(q[2]) + " <= log2(1.1)) never rises by 10 % on doubling: no saturation point";
    }
    if (!fit.fitted || !fit.point.exists || dof <= 0) return fit;

    // Standard errors: the covariance s^2 (J^T J)^-1 of the scaled parameters, carried to T and
    // h(T) by their gradients (central differences).
    Eigen::VectorXd r;
    Eigen::MatrixXd J;
    residuals(s, q, fit.parameters, r, J);
    const Eigen::MatrixXd H = J.transpose() * J;
    Eigen::FullPivLU<Eigen::MatrixXd> lu(H);
    if (!lu.isInvertible()) return fit;
    const Eigen::MatrixXd covariance = lu.inverse() * ((r.squaredNorm() + s.within) / dof);
    Eigen::VectorXd grad_t(fit.parameters), grad_i(fit.parameters);
    for (int j = 0; j < fit.parameters; ++j) {
        const double h = 1e-6 * std::max(1.0, std::fabs(q[j]));
        Params up = q, down = q;
        up[j] += h;
        down[j] -= h;
        const SaturationPoint pu = saturation_point(physical(s, up)), pd = saturation_point(physical(s, down));
        if (!pu.exists || !pd.exists) return fit;
        grad_t[j] = (pu.time - pd.time) / (2.0 * h);
        grad_i[j] = (pu.intensity - pd.intensity) / (2.0 * h);
    }
    fit.time_standard_error = std::sqrt(std::max(0.0, grad_t.dot(covariance * grad_t)));
    fit.intensity_standard_error = std::sqrt(std::max(0.0, grad_i.dot(covariance * grad_i)));
    return fit;
}

SaturationChoice choose_saturation_fit(const SaturationFit& two, const SaturationFit& three) {
    SaturationChoice choice;
    const bool two_ok = two.fitted && two.point.exists, three_ok = three.fitted && three.point.exists;
    choice.any = two_ok || three_ok;
    if (!choice.any) {
        choice.reason = "neither fit gives a saturation point";
        return choice;
    }
    if (!two_ok) {
        choice.form = SaturationForm::three_parameter;
        choice.reason = "the 2P fit has no saturation point (" + two.problem + ")";
        return choice;
    }
    if (!three_ok) {
        choice.reason = "the 3P fit is not usable (" + (three.problem.empty() ? std::string("no saturation point") : three.problem) + ")";
        return choice;
    }
    const int n = two.points;
    if (two.rms_residual <= kExactFit * two.curve.a) {
        choice.reason = "the 2P form already fits every strip to rounding";
        return choice;
    }
    if (n < 5) {
        choice.reason = "with " + std::to_string(n) +
                        " points the 3P fit leaves too few degrees of freedom (it needs 5 points or more) to show that its third "
                        "parameter is real, so the simpler 2P form is used";
        return choice;
    }
    const double dof = n - 3.0;
    const double ssr2 = two.residual_sum_of_squares, ssr3 = three.residual_sum_of_squares;
    const double F = ssr3 > 0.0 ? std::max(0.0, (ssr2 - ssr3) / (ssr3 / dof)) : std::numeric_limits<double>::infinity();
    const double p = std::isfinite(F) ? student_t_two_sided_tail(std::sqrt(F), dof) : 0.0;  // F(1, dof) = t(dof)^2
    if (p < 0.05) {
        choice.form = SaturationForm::three_parameter;
        choice.reason = "its third parameter lowers the residual significantly (F = " + text(F) + ", p = " + text(p) + " < 0.05)";
    } else {
        choice.reason = "the 3P fit's third parameter does not lower the residual significantly (F = " + text(F) + ", p = " + text(p) +
                        " >= 0.05), so the simpler 2P form is used";
    }
    return choice;
}

}  // namespace peensim
