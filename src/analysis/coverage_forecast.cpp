#include "analysis/coverage_forecast.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <random>
#include <unordered_map>

#include "analysis/cube_keys.h"
#include "analysis/edge_lines.h"
#include "analysis/latest_crossing.h"
#include "analysis/reach_boundary.h"
#include "analysis/sample_mean.h"
#include "analysis/student_t.h"
#include "analysis/surface_cells.h"
#include "analysis/surface_kernel.h"
#include "common/float_limits.h"
#include "common/parallel_chunks.h"
#include "geometry/mesh_checks.h"

namespace peensim {

namespace {

constexpr int kRadiusRounds = 3;            // h is re-chosen at most this often as the extrapolation settles
constexpr double kRadiusSettled = 0.25;     // relative change of the extrapolation below which h stays
constexpr int kRootIterations = 60;         // bisection steps on the span
constexpr double kLargestSpan = 1e6;        // tau / T beyond which a target counts as never reached
constexpr double kRestAreaShare = 1e-6;     // a rest smaller than this share of the peened area is round-off of the regions
constexpr double kLeastThinnedShare = 0.1;  // the kernel left to an impact after its hole, at least (see "The selection")

// exp(-x) for x >= 0: what std::exp gives, +0 included, without its underflow path (errno and
// a floating-point exception for every exponent beyond 1024: the searches for a span try spans
// far past the target, where most terms are gone; 4 % of an analysis).
double exp_of_minus(double x) { return x >= 1024.0 ? 0.0 : std::exp(-x); }

// An edge group (surface_cells.h) with its means: the samples of one cell and class near the same
// one or two edge lines, each in the same band of distance to it.
struct EdgeGroupMean {
    std::uint32_t cell = 0;
    std::uint16_t cls = 0;
    std::int32_t line[2] = {-1, -1};
    double uncovered_m2 = 0.0;          // m2
    double s_m[2] = {0.0, 0.0};         // m, the area-weighted mean position along each line
    double distance_m[2] = {0.0, 0.0};  // m, and distance to it
};

// A reach group (surface_cells.h) with its mean distance to the boundary.
struct ReachGroupMean {
    std::uint32_t cell = 0;
    std::uint16_t cls = 0;
    double uncovered_m2 = 0.0;  // m2
    double distance_m = 0.0;    // m, the area-weighted mean distance to the boundary
};

// What an area holds of a cell (m2); group >= 0: of the cell's samples near an edge line, that
// group's (EdgeGroup).
struct AreaTerm {
    std::uint32_t cell = 0;
    double m2 = 0.0;
    std::int32_t group = -1;
    std::int32_t reach_group = -1;  // >= 0: of the cell's samples near a reach boundary (ReachGroup)
};

// The 1D quartic kernel along an edge line centred at s, (1 - (u - s)^2/h^2)^2, integrated over
// [from, to] (m): over the line's part [0, length], the normalisation of a density estimated along
// it.
double quartic_line_integral(double s, double from, double to, double h) {
    const auto F = [](double x) { return x - 2.0 * x * x * x / 3.0 + x * x * x * x * x / 5.0; };
    const double hi = std::min(1.0, (to - s) / h), lo = std::max(-1.0, (from - s) / h);
    return hi > lo ? h * (F(hi) - F(lo)) : 0.0;
}

// The estimator's series (see the header): -log of the survival over a span s, sum_j s^j S_j / j
// with S_j = sum_i kappa_i^j; m[j] holds S_(j+1) / (j + 1). Six terms, not three: with s kappa up to
// q = 0.5 the fourth term alone is 1.6 % of an impact's share, and dropping it and the rest made an
// evenly peened cube (equal dents, every one at a_q) forecast 1.4 % late at h, a bias the 2 h
// forecast then doubled as a "smoothing correction"; with six the cube comes out +0.1 % at h.
constexpr std::size_t kSeriesTerms = 6;
double series(const std::array<double, kSeriesTerms>& m, double s) {
    double sum = 0.0;
    for (std::size_t j = kSeriesTerms; j-- > 0;) sum = (sum + m[j]) * s;
    return sum;
}
double series_slope(const std::array<double, kSeriesTerms>& m, double s) {  // d series / d s
    double sum = 0.0;
    for (std::size_t j = kSeriesTerms; j-- > 0;) sum = sum * s + static_cast<double>(j + 1) * m[j];
    return sum;
}
void add_powers(double* sums, double w) {  // sums[j] += w^(j + 1)
    double power = 1.0;
    for (std::size_t j = 0; j < kSeriesTerms; ++j) sums[j] += (power *= w);
}

// The quartic kernel's integral over a flat disc of radius rho about its centre (m2).
double quartic_disc_integral(double rho, double h) {
    const double r2 = std::min(rho * rho, h * h) / (h * h);
    return M_PI * h * h * (r2 - r2 * r2 + r2 * r2 * r2 / 3.0);
}

// The run's own noise. The forecast is the expected uncovered area; the run that is checked against
// it is one draw. For a stationary Boolean model of dents of area a (radius rho) at a point that has
// had m_T dents expected so far and m_t by the target, two points r apart, both uncovered now, stay
// both uncovered with exp(-(m_t - m_T)(2 - g(r))), g the two dents' overlap share (the dents that
// would cover both); their covariance, integrated over r and divided by the chance exp(-m_T) of a
// point being uncovered now, gives the variance per uncovered area now:
//   a exp(m_T - 2 m_t) 2 int_0^2 (exp(m_t g(u)) - exp(m_T g(u))) u du,  u = r / rho.
// Summed over the uncovered samples and divided by the slope of the uncovered area it gives the
// spread of the time at which the run crosses the target: added to the jackknife's.
constexpr double kMostDents = 200.0;  // expected dents beyond which exp would overflow (none are so deep)

double disc_overlap_share(double u) {  // two discs of radius 1, u apart: their overlap over one's area
    if (u >= 2.0) return 0.0;
    const double h = 0.5 * u;
    return (2.0 / M_PI) * (std::acos(h) - h * std::sqrt(1.0 - h * h));
}

double uncovered_pair_integral(double m_now, double m_then) {
    // Midpoints of u = 2 w^2 (w in [0, 1]): the integrand gathers at u ~ 1 / m.
    constexpr int kPoints = 48;
    double sum = 0.0;
    for (int i = 0; i < kPoints; ++i) {
        const double w = (i + 0.5) / kPoints, u = 2.0 * w * w, du = 4.0 * w / kPoints;
        const double g = disc_overlap_share(u);
        sum += (std::exp(m_then * g + m_now - 2.0 * m_then) - std::exp(m_now * g + m_now - 2.0 * m_then)) * u * du;
    }
    return 2.0 * sum;
}

// The selection of the uncovered. A sample still uncovered has, by that very fact, no impact
// whose dent would have covered it: none within its dent radius rho_i around it (along an edge
// line: within the chord). The impacts that did not cover it are independent of that (a Poisson
// process thinned by where its points fall), but they are fewer than the kernel expects by the
// kernel's mass over that hole; each impact's kappa is divided by the kernel's integral less its
// own hole, so that the sums estimate the rate the uncovered sample will see. Without it the
// rates come out low by the hole's share, 14 % for a dent radius of a fifth of h (a long window
// forecasting a short way: a 60 s run of a part 97 % covered).

// The kernel sums of one radius h over the surface's cells of side h / kForecastCellsPerRadius, and
// the spans they forecast.
class KernelField {
public:
    // cells: the surface in cells of side about radius_m / kForecastCellsPerRadius (CellsForRadius).
    KernelField(const SurfaceCells& cells, const TriangleMesh& mesh, std::span<const ForecastImpact> impacts, const EdgeLines& edges,
                int batches, const std::vector<bool>& batch_used, double radius_m, double line_radius_m,
                const std::vector<std::vector<std::uint32_t>>& areas_of_class, std::size_t area_count)
        : batches_(batches), batch_used_(batch_used), radius_(radius_m), line_radius_(line_radius_m) {
        adopt(cells, areas_of_class, area_count);
        build_neighbours();
        sum_kernels(mesh, impacts);
        sum_edges(edges);
    }

    std::size_t uncovered_cells() const { return uncovered_cells_; }

    // tau / T_rate (the extrapolation span) at which area a's uncovered area falls to remaining_m2,
    // from the batches in use but `left_out` (-1: none); +inf: never; 0: already.
    double span_to(std::size_t a, double remaining_m2, int left_out) const {
        const std::vector<AreaTerm>& terms = terms_[a];
        // Scratch of its own on every thread (the areas' spans are found on every core).
        thread_local std::vector<std::array<double, kSeriesTerms>> moments;
        moments.resize(terms.size());
        double never = 0.0, now = 0.0;  // m2: uncovered with no impact within h; uncovered now
        for (std::size_t k = 0; k < terms.size(); ++k) {
            moments[k] = term_moments(terms[k], left_out);
            now += terms[k].m2;
            if (!(moments[k][0] > 0.0)) never += terms[k].m2;
        }
        if (now <= remaining_m2) return 0.0;
        if (never >= remaining_m2) return kInf;
        // The uncovered area at span s (m2), and its slope (m2 per unit of span).
        const auto uncovered = [&](double s, double& slope) {
            double u = 0.0;
            slope = 0.0;
            for (std::size_t k = 0; k < terms.size(); ++k) {
                const auto& m = moments[k];
                const double kept = terms[k].m2 * exp_of_minus(series(m, s));
                u += kept;
                slope -= kept * series_slope(m, s);
            }
            return u;
        };
        double lo = 0.0, hi = 1.0, slope = 0.0;
        while (uncovered(hi, slope) > remaining_m2) {
            lo = hi;
            hi *= 2.0;
            if (hi > kLargestSpan) return kInf;
        }
        // Newton's method on log(uncovered), which is nearly straight in s, kept inside the
        // bracket [lo, hi] (a step that leaves it bisects instead): a handful of evaluations where
        // bisection took forty.
        double s = lo > 0.0 ? std::sqrt(lo * hi) : 0.5 * hi;
        for (int i = 0; i < kRootIterations && hi - lo > 1e-9 * hi; ++i) {
            const double u = uncovered(s, slope);
            (u > remaining_m2 ? lo : hi) = s;
            double next = u > 0.0 && slope < 0.0 ? s - std::log(u / remaining_m2) * u / slope : kNaN;
            if (!(next > lo && next < hi)) next = lo > 0.0 ? std::sqrt(lo * hi) : 0.5 * hi;
            if (std::abs(next - s) <= 1e-12 * s) return next;
            s = next;
        }
        return s;
    }

    // The spread of the run itself about that forecast (see "The run's own noise" in the header):
    // the variance (m4) of area a's uncovered area at `span`, and its slope there (m2 per unit of
    // span), from every uncovered term as a stationary Boolean model of dents of area dent_area_m2
    // (m2) that has had window_per_rate x its moment m1 of dents so far.
    void uncovered_spread(std::size_t a, double span, double dent_area_m2, double window_per_rate, double& variance_m4,
                          double& slope_m2) const {
        variance_m4 = slope_m2 = 0.0;
        for (const AreaTerm& t : terms_[a]) {
            const auto m = term_moments(t, -1);
            if (!(m[0] > 0.0)) continue;
            const double future = series(m, span);      // dents expected from now on
            const double rate = series_slope(m, span);  // d future / d span
            const double kept = exp_of_minus(future);
            slope_m2 += t.m2 * kept * rate;
            const double so_far = std::min(m[0] * window_per_rate, kMostDents);
            variance_m4 += t.m2 * dent_area_m2 * uncovered_pair_integral(so_far, std::min(so_far + future, kMostDents));
        }
    }

private:
    // The exponent's series of a term: sum_m s^m S_m / m, S_m = sum kappa^m, over the
    // face impacts (normalised here) and the edge impacts (normalised as summed); the batches in
    // use but `left_out` (-1: none).
    std::array<double, kSeriesTerms> term_moments(const AreaTerm& t, int left_out) const {
        const std::size_t c = t.cell;
        std::array<double, kSeriesTerms> m{}, e{};
        for (int b = 0; b < batches_; ++b) {
            if (!batch_used_[static_cast<std::size_t>(b)] || b == left_out) continue;
            const double* s = t.reach_group >= 0
                                  ? &reach_sums_[(static_cast<std::size_t>(t.reach_group) * static_cast<std::size_t>(batches_) +
                                                  static_cast<std::size_t>(b)) *
                                                 kSeriesTerms]
                                  : &sums_[(c * static_cast<std::size_t>(batches_) + static_cast<std::size_t>(b)) * kSeriesTerms];
            for (std::size_t j = 0; j < kSeriesTerms; ++j) m[j] += s[j];
            if (t.group < 0) continue;
            const double* x =
                &edge_sums_[(static_cast<std::size_t>(t.group) * static_cast<std::size_t>(batches_) + static_cast<std::size_t>(b)) *
                            kSeriesTerms];
            for (std::size_t j = 0; j < kSeriesTerms; ++j) e[j] += x[j];
        }
        const double inv = norm_[c] > 0.0 ? 1.0 / norm_[c] : 0.0;
        double power = 1.0;
        for (std::size_t j = 0; j < kSeriesTerms; ++j) {
            power *= inv;
            m[j] = (m[j] * power + e[j]) / static_cast<double>(j + 1);
        }
        return m;
    }

    void adopt(const SurfaceCells& cells, const std::vector<std::vector<std::uint32_t>>& areas_of_class, std::size_t area_count) {
        const std::size_t n = cells.reach_m2.size();
        reach_m2_ = cells.reach_m2;
        centroid_.resize(n);
        normal_.resize(n);
        for (std::size_t c = 0; c < n; ++c) {
            // A cell of unreachable samples only (of a triangle crossing the reach boundary) has no
            // area: its cube's centre stands in.
            centroid_[c] = reach_m2_[c] > 0.0 ? Vec3(cells.point_sum[c] / reach_m2_[c])
                                              : Vec3((Vec3(static_cast<double>(cells.cube[c][0]), static_cast<double>(cells.cube[c][1]),
                                                           static_cast<double>(cells.cube[c][2])) +
                                                      Vec3::Constant(0.5)) *
                                                     cells.side);
            const double norm = cells.normal_sum[c].norm();
            normal_[c] = norm > 0.0 ? Vec3(cells.normal_sum[c] / norm) : Vec3::Zero();
        }
        // Each area's cells with their uncovered area (the pairs are in cell order).
        terms_.assign(area_count, {});
        uncovered_cell_.assign(n, false);
        for (const auto& [pair, m2] : cells.uncovered) {
            const auto c = static_cast<std::uint32_t>(pair >> 16);
            uncovered_cell_[c] = true;
            for (std::uint32_t a : areas_of_class[pair & 0xFFFF]) {
                std::vector<AreaTerm>& terms = terms_[a];
                if (!terms.empty() && terms.back().cell == c)
                    terms.back().m2 += m2;
                else
                    terms.push_back({c, m2});
            }
        }
        // The samples near the reach boundary: a term per group, and each cell's groups.
        reach_groups_.clear();
        for (const ReachGroup& g : cells.reach_groups)
            reach_groups_.push_back({g.cell, g.cls, g.uncovered_m2, g.distance_sum_m3 / g.uncovered_m2});
        reach_first_.assign(n + 1, 0);
        for (const ReachGroupMean& g : reach_groups_) ++reach_first_[g.cell + 1];
        for (std::size_t c = 0; c < n; ++c) reach_first_[c + 1] += reach_first_[c];
        for (std::size_t g = 0; g < reach_groups_.size(); ++g) {
            const ReachGroupMean& group = reach_groups_[g];
            uncovered_cell_[group.cell] = true;
            for (std::uint32_t a : areas_of_class[group.cls])
                terms_[a].push_back({group.cell, group.uncovered_m2, -1, static_cast<std::int32_t>(g)});
        }
        // The samples near edge lines: a term per group.
        groups_.clear();
        for (const EdgeGroup& g : cells.edge_groups) {
            EdgeGroupMean mean{g.cell, g.cls, {g.line[0], g.line[1]}, g.uncovered_m2};
            for (int m = 0; m < 2; ++m)
                mean.s_m[m] = g.s_sum_m3[m] / g.uncovered_m2, mean.distance_m[m] = g.distance_sum_m3[m] / g.uncovered_m2;
            groups_.push_back(mean);
        }
        for (std::size_t g = 0; g < groups_.size(); ++g) {
            uncovered_cell_[groups_[g].cell] = true;
            for (std::uint32_t a : areas_of_class[groups_[g].cls])
                terms_[a].push_back({groups_[g].cell, groups_[g].uncovered_m2, static_cast<std::int32_t>(g)});
        }
        uncovered_cells_ = static_cast<std::size_t>(std::count(uncovered_cell_.begin(), uncovered_cell_.end(), true));
    }

    // Cells by cube of side h around their centroids: every cell within h of a point lies in the
    // 27 cubes around it.
    void build_neighbours() {
        const double inverse = 1.0 / radius_;
        std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(centroid_.size());
        for (std::size_t c = 0; c < centroid_.size(); ++c) {
            const auto q = cube_of(centroid_[c], inverse);
            keyed[c] = {cube_key(q[0], q[1], q[2], -1), static_cast<std::uint32_t>(c)};
        }
        index_by_cube(keyed, grid_, grid_cells_);
    }

    template <class Visit>
    void for_each_cell_near(const Vec3& p, Visit&& visit) const {
        const double r2 = radius_ * radius_;
        const auto q = cube_of(p, 1.0 / radius_);
        for (std::int64_t dz = -1; dz <= 1; ++dz)
            for (std::int64_t dy = -1; dy <= 1; ++dy)
                for (std::int64_t dx = -1; dx <= 1; ++dx) {
                    const auto* run = grid_.find(cube_key(q[0] + dx, q[1] + dy, q[2] + dz, -1));
                    if (run == nullptr) continue;
                    for (std::uint32_t i = run->first; i < run->second; ++i) {
                        const std::uint32_t c = grid_cells_[i];
                        const double d2 = (centroid_[c] - p).squaredNorm();
                        if (d2 < r2) visit(c, d2);
                    }
                }
    }

    void sum_kernels(const TriangleMesh& mesh, std::span<const ForecastImpact> impacts) {
        const double inv_r2 = 1.0 / (radius_ * radius_);
        const std::size_t cells = centroid_.size();
        norm_.assign(cells, 0.0);
        for (std::size_t c = 0; c < cells; ++c) {
            if (!uncovered_cell_[c]) continue;
            for_each_cell_near(centroid_[c], [&](std::uint32_t q, double d2) {
                norm_[c] += quartic(d2, inv_r2) * std::max(0.0, normal_[c].dot(normal_[q])) * reach_m2_[q];
            });
        }
        sums_.assign(cells * static_cast<std::size_t>(batches_) * kSeriesTerms, 0.0);
        reach_sums_.assign(reach_groups_.size() * static_cast<std::size_t>(batches_) * kSeriesTerms, 0.0);
        for (const ForecastImpact& i : impacts) {
            if (i.edge >= 0) continue;  // along its edge line (sum_edges)
            const Vec3 p(i.point_m[0], i.point_m[1], i.point_m[2]);
            const Vec3 n = triangle_normal(mesh, i.triangle);
            const double a = i.dent_area_m2;
            const double rho = std::sqrt(a / M_PI);                                   // m, the dent's radius
            const double hole = quartic_disc_integral(std::sqrt(a / M_PI), radius_);  // m2
            for_each_cell_near(p, [&](std::uint32_t c, double d2) {
                if (!uncovered_cell_[c]) return;
                // w a N / (N - hole): divided by N in span_to, kappa = w a / (N - hole).
                const double thinned = norm_[c] / std::max(norm_[c] - hole, kLeastThinnedShare * norm_[c]);
                const double w = quartic(d2, inv_r2) * std::max(0.0, normal_[c].dot(n)) * a * thinned;
                if (!(w > 0.0)) return;
                add_powers(&sums_[(c * static_cast<std::size_t>(batches_) + i.batch) * kSeriesTerms], w);
                // Near the reach boundary only the dent's share on the reachable side covers.
                for (std::uint32_t g = reach_first_[c]; g < reach_first_[c + 1]; ++g)
                    add_powers(&reach_sums_[(g * static_cast<std::size_t>(batches_) + i.batch) * kSeriesTerms],
                               w * disc_share_inside(reach_groups_[g].distance_m, rho));
            });
        }
    }

    // Each edge group's sums of kappa_j = K(s - s_j) / (its integral) 2 sqrt(rho_j^2 - d^2) over the
    // impacts of its line within h along it, per batch (see the header).
    void sum_edges(const EdgeLines& edges) {
        edge_sums_.assign(groups_.size() * static_cast<std::size_t>(batches_) * kSeriesTerms, 0.0);
        const double h = line_radius_, inv_h2 = 1.0 / (h * h);
        for (std::size_t g = 0; g < groups_.size(); ++g) {
            const EdgeGroupMean& group = groups_[g];
            for (int m = 0; m < 2; ++m) {
                if (group.line[m] < 0) continue;
                const EdgeLines::Line& line = edges.lines[static_cast<std::size_t>(group.line[m])];
                const double foot = group.s_m[m];  // may lie off the segment
                const double at = std::clamp(foot, 0.0, line.length_m);
                const double norm = quartic_line_integral(at, 0.0, line.length_m, h);
                if (!(norm > 0.0)) continue;
                const auto begin = edges.impacts.begin() + static_cast<std::ptrdiff_t>(line.first);
                const auto end = begin + static_cast<std::ptrdiff_t>(line.count);
                auto it = std::lower_bound(begin, end, at - h, [](const EdgeLines::Impact& i, double s) { return i.s_m < s; });
                const double d2 = group.distance_m[m] * group.distance_m[m];
                for (; it != end && it->s_m <= at + h; ++it) {
                    const double chord2 = it->radius_m * it->radius_m - d2;
                    if (!(chord2 > 0.0)) continue;
                    // The part of the covering chord that lies on this segment (the rest belongs
                    // to the next one's impacts).
                    const double half = std::sqrt(chord2);
                    const double from = std::max(0.0, foot - half), to = std::min(line.length_m, foot + half);
                    const double on_segment = to - from;
                    if (!(on_segment > 0.0)) continue;
                    const double u = at - it->s_m;
                    // Its own hole: the chord, where an impact would have covered the sample.
                    const double hole = quartic_line_integral(at, from, to, h);
                    const double w = quartic(u * u, inv_h2) / std::max(norm - hole, kLeastThinnedShare * norm) * on_segment;
                    if (!(w > 0.0)) continue;
                    add_powers(&edge_sums_[(g * static_cast<std::size_t>(batches_) + it->batch) * kSeriesTerms], w);
                }
            }
        }
    }

    int batches_;
    std::vector<bool> batch_used_;
    double radius_;
    double line_radius_;  // m, along edge lines
    std::vector<EdgeGroupMean> groups_;
    std::vector<ReachGroupMean> reach_groups_;
    std::vector<std::uint32_t> reach_first_;  // per cell: its reach groups [reach_first_[c], reach_first_[c + 1])
    std::vector<double> reach_sums_;          // per reach group, batch: sums of (w a f)^1 .. (w a f)^kSeriesTerms
    std::vector<double> edge_sums_;           // per edge group, batch: sums of kappa^1 .. kappa^kSeriesTerms
    // Cells (structure of arrays).
    std::vector<double> reach_m2_;  // m2: reachable area
    std::vector<Vec3> centroid_;    // m
    std::vector<Vec3> normal_;      // unit
    std::vector<bool> uncovered_cell_;
    std::vector<double> norm_;                  // m2: sum_q w A_q
    std::vector<double> sums_;                  // per cell, batch: sums of (w a)^1 .. (w a)^kSeriesTerms (m2, m4, ...)
    std::vector<std::vector<AreaTerm>> terms_;  // per area: its cells' uncovered area
    std::size_t uncovered_cells_ = 0;
    CubeRuns grid_;
    std::vector<std::uint32_t> grid_cells_;
};

// The surface's cells for each kernel radius h: the samples binned at side h / kForecastCellsPerRadius
// for each h tried, and the cells of 2 h (the smoothing bias) joined 2 x 2 x 2 from those of h (the
// cubes nest exactly), without another pass over the samples. (Binning at an eighth of that side,
// to make up later radii from the same fine cells, paid only for 2 h: the radii come from a
// formula, no later one was a whole multiple of the fine side, and every pass walked 8^3 times the
// cells.)
class CellsForRadius {
public:
    CellsForRadius(const CoverageProgress& progress, const TriangleMesh& mesh, const EdgeLines& edges, const ReachBoundary& boundary)
        : progress_(progress), mesh_(mesh), edges_(edges), boundary_(boundary) {}

    // Valid until the next call.
    const SurfaceCells& at(double radius_m) {
        const double side = radius_m / kForecastCellsPerRadius;
        if (binned_ && binned_->side == side) return *binned_;
        if (binned_ && 2.0 * binned_->side == side) return joined_.emplace(binned_->coarsened(2));
        return binned_.emplace(progress_, mesh_, edges_, boundary_, side);
    }

private:
    const CoverageProgress& progress_;
    const TriangleMesh& mesh_;
    const EdgeLines& edges_;
    const ReachBoundary& boundary_;
    std::optional<SurfaceCells> binned_, joined_;
};

// Which batches the rates come from: all but the first when that is a start-up transient (its
// dent area off the others' mean by more than kStartupSigmas of their spread).
std::vector<bool> batches_in_use(std::span<const ForecastImpact> impacts, int batches, bool& startup) {
    std::vector<double> dent(static_cast<std::size_t>(batches), 0.0);
    for (const ForecastImpact& i : impacts) dent[i.batch] += i.dent_area_m2;
    std::vector<bool> used(static_cast<std::size_t>(batches), true);
    startup = false;
    if (batches >= 4) {
        const SampleMean others = sample_mean(std::span<const double>(dent).subspan(1));
        const double sd = others.standard_error * std::sqrt(static_cast<double>(others.count));
        if (sd > 0.0 && std::abs(dent[0] - others.mean) > kStartupSigmas * sd) {
            used[0] = false;
            startup = true;
        }
    }
    return used;
}

// The drift of the dent-area rate over the used batches: a least-squares line through them (its
// standard error from their scatter about it, so an overdispersed rate is not called a drift).
struct RateDrift {
    double change = 0.0;  // -, fitted last used batch over first, less one, relative to the mean
    bool significant = false;
};
RateDrift rate_drift(std::span<const ForecastImpact> impacts, int batches, const std::vector<bool>& used) {
    std::vector<double> dent(static_cast<std::size_t>(batches), 0.0);
    for (const ForecastImpact& i : impacts) dent[i.batch] += i.dent_area_m2;
    std::vector<double> x, y;
    for (int b = 0; b < batches; ++b)
        if (used[static_cast<std::size_t>(b)]) x.push_back(b), y.push_back(dent[static_cast<std::size_t>(b)]);
    const double n = static_cast<double>(x.size());
    if (x.size() < 4) return {};
    const double mx = std::accumulate(x.begin(), x.end(), 0.0) / n, my = std::accumulate(y.begin(), y.end(), 0.0) / n;
    double sxx = 0.0, sxy = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) sxx += (x[k] - mx) * (x[k] - mx), sxy += (x[k] - mx) * (y[k] - my);
    if (!(sxx > 0.0) || !(my > 0.0)) return {};
    const double slope = sxy / sxx;
    double ssr = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) ssr += std::pow(y[k] - (my + slope * (x[k] - mx)), 2);
    const double se = std::sqrt(ssr / (n - 2.0) / sxx);
    RateDrift d;
    d.change = slope * (x.back() - x.front()) / my;
    d.significant = se > 0.0 ? std::abs(slope) > kDriftSigmas * se : slope != 0.0;
    return d;
}

// The smallest kernel: kHoleMargin dent radii (of a_q). An uncovered point has no impact within a
// dent radius of it, so a kernel that reaches no farther sees none and says "never"; a short
// extrapolation (a long run near its target) would otherwise shrink h below that.
double smallest_radius(double dent_area_q) { return kHoleMargin * std::sqrt(dent_area_q / M_PI); }

// The radius that keeps s kappa <= q for the dent area a_q at span s (see the header), at least
// the smallest.
double radius_for(double span, double dent_area_q) {
    return std::max(std::sqrt(3.0 * span * dent_area_q / (M_PI * kForecastKappaBound)), smallest_radius(dent_area_q));
}

// Along an edge line: kappa_j peaks at the largest chord 2 rho over the 1D kernel's integral
// 16 h / 15, so s kappa <= q asks for h >= 15 s rho_q / (8 q) (rho_q the dent radius of a_q), and
// never less than the areal radius.
double line_radius_for(double span, double dent_area_q, double radius) {
    return std::max(radius, 15.0 * span * std::sqrt(dent_area_q / M_PI) / (8.0 * kForecastKappaBound));
}

// log(tau) of the jackknife replicates -> its standard error (infinite when a replicate never
// reaches the target).
double jackknife_se(const std::vector<double>& taus) {
    if (taus.size() < 2) return kInf;
    std::vector<double> logs;
    for (double t : taus) {
        if (!std::isfinite(t)) return kInf;
        logs.push_back(std::log(std::max(t, 1e-300)));
    }
    const double n = static_cast<double>(logs.size());
    const double mean = std::accumulate(logs.begin(), logs.end(), 0.0) / n;
    double ss = 0.0;
    for (double l : logs) ss += (l - mean) * (l - mean);
    return std::sqrt(ss * (n - 1.0) / n);
}

}  // namespace

const char* status_name(AreaForecast::Status s) {
    switch (s) {
        case AreaForecast::Status::reached: return "reached";
        case AreaForecast::Status::forecast: return "forecast";
        case AreaForecast::Status::too_short: return "too_short";
        case AreaForecast::Status::never: return "never";
        case AreaForecast::Status::none: return "none";
    }
    return "none";
}

CoverageForecast forecast_coverage(const CoverageProgress& progress, const TriangleMesh& mesh, std::span<const ForecastImpact> impacts,
                                   double window_s, int batches, const ReachedAfterWindow& later) {
    const SampleClasses& classes = progress.classes();
    const double target = progress.target();
    const std::size_t regions = classes.region_count();
    const std::size_t areas = regions + 2;  // 0: the peened area, 1 + r: region r, last: the rest
    const std::size_t rest = areas - 1;
    CoverageForecast f;
    f.summary.window_s = window_s;
    // The largest dent's radius (m): how far an edge line or the reach boundary matters.
    float largest_dent_m2 = 0.0f;
    for (const ForecastImpact& i : impacts) largest_dent_m2 = std::max(largest_dent_m2, i.dent_area_m2);
    const double reach_m = std::sqrt(largest_dent_m2 / M_PI);
    const EdgeLines edges(mesh, impacts, reach_m);
    f.summary.edge_impacts = edges.count;
    f.summary.face_impacts = impacts.size() - edges.count;
    f.summary.edge_lines = edges.lines.size();
    f.regions.resize(regions);

    // The areas: their classes, area (m2), coverage now, when reached; which are forecast.
    std::vector<std::vector<std::uint32_t>> areas_of_class(classes.size());
    std::vector<double> area_m2(areas, 0.0);
    std::vector<AreaForecast> out(areas);
    std::vector<bool> counted(areas, false);
    for (std::size_t k = 0; k < classes.size(); ++k) {
        const auto kk = static_cast<std::uint16_t>(k);
        if (!classes.info(kk).peened()) continue;
        areas_of_class[k].push_back(0);
        bool in_counted = false;
        for (std::uint32_t r : classes.info(kk).regions) {
            areas_of_class[k].push_back(r + 1);
            in_counted = in_counted || !classes.region_excluded(r);
        }
        if (!in_counted) areas_of_class[k].push_back(static_cast<std::uint32_t>(rest));
    }
    area_m2[0] = classes.peened_area_m2();
    out[0].coverage_now = progress.coverage();
    out[0].time_s = progress.reached_at_s();
    counted[0] = area_m2[0] > 0.0;
    for (std::size_t r = 0; r < regions; ++r) {
        area_m2[r + 1] = classes.region_peened_area_m2(r);
        out[r + 1].coverage_now = progress.region_coverage(r);
        out[r + 1].time_s = progress.region_reached_at_s(r);
        counted[r + 1] = !classes.region_excluded(r) && area_m2[r + 1] > 0.0;
    }
    // The rest of the peened area (a sliver left by regions that do not quite tile it is no area).
    area_m2[rest] = progress.rest_area_m2();
    out[rest].coverage_now = progress.rest_coverage();
    out[rest].time_s = progress.rest_reached_at_s();
    counted[rest] = area_m2[rest] > kRestAreaShare * area_m2[0];
    // Reached after the window, as the caller knows: reached then (without regions the rest is the
    // peened area itself).
    const auto reached_later = [&](std::size_t a, double t) {
        if (counted[a] && !std::isfinite(out[a].time_s) && std::isfinite(t)) out[a].time_s = t, out[a].seen_in_run = true;
    };
    reached_later(0, later.whole_s);
    if (regions == 0) reached_later(rest, later.whole_s);
    for (std::size_t r = 0; r < regions && r < later.region_s.size(); ++r) reached_later(r + 1, later.region_s[r]);
    for (std::size_t a = 0; a < areas; ++a) {
        AreaForecast& o = out[a];
        if (counted[a] && std::isfinite(o.time_s)) {
            o.status = AreaForecast::Status::reached;
            o.low_s = o.high_s = o.noise_high_s = o.time_s;
        } else {
            o.time_s = o.low_s = o.high_s = o.noise_high_s = kNaN;
        }
    }
    const auto pending = [&](std::size_t a) { return counted[a] && out[a].status != AreaForecast::Status::reached; };
    // Everywhere: over the counted regions and the rest (all of the peened area without regions).
    std::vector<std::size_t> everywhere_areas;
    for (std::size_t a = 1; a < areas; ++a)
        if (counted[a]) everywhere_areas.push_back(a);

    bool startup = false;
    const std::vector<bool> used = batches_in_use(impacts, batches, startup);
    const int used_count = static_cast<int>(std::count(used.begin(), used.end(), true));
    const double rate_window = window_s * used_count / batches;
    f.summary.startup_left_out = startup;
    const RateDrift drift = rate_drift(impacts, batches, used);
    f.summary.rate_change = drift.change;
    f.summary.rate_drifts = drift.significant;
    f.summary.batches = used_count;
    f.summary.rate_window_s = rate_window;

    const bool any_pending = std::any_of(everywhere_areas.begin(), everywhere_areas.end(), pending) || pending(0);
    if (any_pending && (impacts.empty() || used_count == 0)) {
        for (std::size_t a = 0; a < areas; ++a)
            if (pending(a)) out[a].status = AreaForecast::Status::none;
    } else if (any_pending) {
        // The dent area a_q that sets h.
        std::vector<float> dents;
        dents.reserve(impacts.size());
        for (const ForecastImpact& i : impacts) dents.push_back(i.dent_area_m2);
        const auto q = dents.begin() + static_cast<std::ptrdiff_t>(kForecastDentQuantile * static_cast<double>(dents.size() - 1));
        std::nth_element(dents.begin(), q, dents.end());
        const double dent_q = *q;
        // The dents' area weighted by itself: the run's noise comes in uncovered islands whose size
        // goes with the larger dents.
        double dent_sum = 0.0, dent_sum2 = 0.0;
        for (const ForecastImpact& i : impacts)
            dent_sum += i.dent_area_m2, dent_sum2 += static_cast<double>(i.dent_area_m2) * i.dent_area_m2;
        const double dent_spread_area = dent_sum > 0.0 ? dent_sum2 / dent_sum : 0.0;
        const ReachBoundary boundary(progress, mesh, reach_m);

        // The first extrapolation span: as if each area's rate were even (C = 1 - exp(-k t)), doubled.
        double span = 0.0;
        for (std::size_t a = 0; a < areas; ++a) {
            if (!pending(a)) continue;
            const double c = std::clamp(out[a].coverage_now, 1e-9, target);
            span = std::max(span, 2.0 * std::log((1.0 - c) / (1.0 - target)) / -std::log1p(-c));
        }
        span = std::clamp(span, 0.1, kLargestSpan);
        const auto remaining = [&](std::size_t a) { return (1.0 - target) * area_m2[a]; };

        CellsForRadius cells(progress, mesh, edges, boundary);
        std::vector<double> spans(areas, kNaN);
        double radius = radius_for(span, dent_q);
        for (int round = 0; round < kRadiusRounds; ++round) {
            radius = radius_for(span, dent_q);
            const double line_radius = line_radius_for(span, dent_q, radius);
            const KernelField field(cells.at(radius), mesh, impacts, edges, batches, used, radius, line_radius, areas_of_class, areas);
            f.summary.cells = field.uncovered_cells();
            // Each area's span on every core (the whole part's alone is as long as its regions' together).
            for_each_chunk(areas, [&](std::size_t a) {
                if (pending(a)) spans[a] = field.span_to(a, remaining(a), -1);
            });
            double slowest = 0.0;
            for (std::size_t a = 0; a < areas; ++a)
                if (pending(a) && std::isfinite(spans[a])) slowest = std::max(slowest, spans[a]);
            const bool settled = slowest > 0.0 && std::abs(slowest - span) <= kRadiusSettled * span;
            if (slowest > 0.0) span = slowest;
            if (!settled && round < kRadiusRounds - 1) continue;

            // The jackknife at h (each used batch left out in turn: the rate window shrinks with
            // it), and the smoothing bias from 2 h.
            const KernelField wide(cells.at(2.0 * radius), mesh, impacts, edges, batches, used, 2.0 * radius, 2.0 * line_radius,
                                   areas_of_class, areas);
            const double quantile = student_t_two_sided_quantile(0.05, std::max(1.0, used_count - 1.0));
            const double left_out_window = rate_window * (used_count - 1) / std::max(1, used_count);
            std::vector<std::vector<double>> replicate(areas);  // per area: tau of each replicate (s), an area a chunk
            for_each_chunk(areas, [&](std::size_t a) {
                if (!pending(a) || !std::isfinite(spans[a])) return;
                for (int b = 0; b < batches; ++b)
                    if (used[static_cast<std::size_t>(b)]) replicate[a].push_back(field.span_to(a, remaining(a), b) * left_out_window);
            });
            // The run's own noise about each forecast (see "The run's own noise"), as a standard
            // deviation of the crossing time (s).
            std::vector<double> process_sd(areas, 0.0);
            for_each_chunk(areas, [&](std::size_t a) {
                if (!pending(a) || !std::isfinite(spans[a])) return;
                double variance = 0.0, slope = 0.0;
                field.uncovered_spread(a, spans[a], dent_spread_area, window_s / rate_window, variance, slope);
                process_sd[a] = slope > 0.0 ? std::sqrt(variance) / slope * rate_window : 0.0;
            });
            // Each area's span at 2 h (the smoothing bias), once.
            std::vector<double> wide_spans(areas, kNaN);
            for_each_chunk(areas, [&](std::size_t a) {
                if (pending(a)) wide_spans[a] = wide.span_to(a, remaining(a), -1);
            });
            const auto finish = [&](AreaForecast& o, double tau, const std::vector<double>& taus, double wide_tau, double sd_s) {
                if (!std::isfinite(tau)) {
                    o.status = AreaForecast::Status::never;
                    o.time_s = o.low_s = o.high_s = o.noise_high_s = kInf;
                    return;
                }
                // The estimate's (jackknife) and the run's own noise, on log(tau).
                const double se = std::hypot(jackknife_se(taus), tau > 0.0 ? sd_s / tau : 0.0);
                // The smoothing bias, linear in h (the rate field jumps at edges and between faces
                // that face the sonotrode differently): tau(0) = tau(h) + (tau(h) - tau(2 h))
                // corrects the point; the interval runs from the uncorrected lower end to the
                // corrected upper one, as the bias is itself an estimate. (The two radii must not
                // differ by the estimator's truncation instead: at three terms of the series they did,
                // by 1.4 % on an evenly peened cube 39x past its window; at six, by 0.3 %.)
                o.bias_s = std::isfinite(wide_tau) ? std::max(0.0, tau - wide_tau) : 0.0;
                o.time_s = window_s + tau + o.bias_s;
                o.low_s = window_s + tau * std::exp(-quantile * se);
                o.noise_high_s = std::isfinite(se) ? window_s + tau * std::exp(quantile * se) : kInf;
                // A wider kernel that forecasts later says the field is not smooth at h's scale
                // (features of the part about h across): the upper end reaches that forecast too.
                const double upper = std::max(tau + o.bias_s, std::isfinite(wide_tau) ? wide_tau : kInf);
                o.high_s = std::isfinite(se) ? window_s + upper * std::exp(quantile * se) : kInf;
                o.status = AreaForecast::Status::forecast;
                if (!(o.high_s <= kTooShortFactor * o.time_s)) {
                    o.status = AreaForecast::Status::too_short;
                    // The spread falls as 1 / sqrt(T) (noise) and sqrt(tau / T) (bias, with h):
                    // the window at which the upper end would come to half the allowed factor.
                    const double spread = o.high_s / o.time_s - 1.0;
                    const double aim = 0.5 * (kTooShortFactor - 1.0);
                    o.run_for_s = std::isfinite(spread) ? window_s * (spread / aim) * (spread / aim) : kInf;
                }
            };
            for (std::size_t a = 0; a < areas; ++a) {
                if (!pending(a)) continue;
                finish(out[a], spans[a] * rate_window, replicate[a], wide_spans[a] * rate_window, process_sd[a]);
            }
            // Everywhere: the slowest counted area, in every replicate, as the latest of the areas'
            // crossings (latest_crossing.h): later than the latest forecast when several are close
            // (each area's run crosses at its own time), earlier by what the forecasts' own error
            // adds to the latest of them (the winner's curse of areas alike).
            if (!everywhere_areas.empty()) {
                double tau = -kInf, wide_tau = -kInf;
                std::vector<double> taus(replicate[everywhere_areas.front()].size(), -kInf);
                std::vector<AreaCrossing> crossings;  // of each pending area
                std::vector<double> wide_taus;        // of each pending area at 2 h, s
                bool any = false;
                for (std::size_t a : everywhere_areas) {
                    if (!pending(a)) continue;
                    any = true;
                    if (spans[a] * rate_window > tau) {
                        tau = spans[a] * rate_window;
                        f.slowest_region = a == rest ? CoverageForecast::kRestOfPart : static_cast<int>(a) - 1;
                    }
                    crossings.push_back({spans[a] * rate_window, process_sd[a], replicate[a]});
                    wide_taus.push_back(wide_spans[a] * rate_window);
                    taus.resize(std::max(taus.size(), replicate[a].size()), -kInf);
                    for (std::size_t k = 0; k < replicate[a].size(); ++k) taus[k] = std::max(taus[k], replicate[a][k]);
                    if (!std::isfinite(spans[a])) taus.assign(taus.size(), kInf);
                }
                double sd = 0.0;
                if (any && std::isfinite(tau)) {
                    const LatestCrossing latest = latest_crossing(crossings);
                    const double shift = latest.mean_s - tau;
                    tau += shift;
                    for (double& t : taus) t += shift;
                    // The smoothing bias: the areas' own (tau(h) - tau(2 h)), each by how often it is
                    // the last (the difference of the latest at h and at 2 h would add the winner's
                    // curse of the noisier h).
                    double bias = 0.0;
                    for (std::size_t k = 0; k < crossings.size(); ++k)
                        if (latest.last_share[k] > 0.0) bias += latest.last_share[k] * (crossings[k].tau_s - wide_taus[k]);
                    wide_tau = std::isfinite(bias) ? tau - bias : kInf;  // a last area never reached at 2 h: no upper end
                    sd = latest.sd_s;
                    f.summary.everywhere_chance_excess_s = latest.chance_excess_s;
                }
                if (any) finish(f.everywhere, tau, taus, wide_tau, sd);
                // Its upper end never below any of its areas' (the point may be: the latest of
                // several forecasts alike is late by chance, see above).
                if (f.everywhere.status == AreaForecast::Status::forecast)
                    for (std::size_t a : everywhere_areas) {
                        if (!pending(a) || out[a].status != AreaForecast::Status::forecast) continue;
                        f.everywhere.high_s = std::max(f.everywhere.high_s, out[a].high_s);
                    }
            }
            break;
        }
        f.summary.radius_m = radius;
    }
    // Everywhere already reached: when its last area did.
    if (f.everywhere.status == AreaForecast::Status::none && !everywhere_areas.empty() &&
        std::all_of(everywhere_areas.begin(), everywhere_areas.end(),
                    [&](std::size_t a) { return out[a].status == AreaForecast::Status::reached; })) {
        f.everywhere.status = AreaForecast::Status::reached;
        f.everywhere.time_s = 0.0;
        for (std::size_t a : everywhere_areas)
            if (out[a].time_s >= f.everywhere.time_s) {
                f.everywhere.time_s = out[a].time_s;
                f.everywhere.seen_in_run = out[a].seen_in_run;
                f.slowest_region = a == rest ? CoverageForecast::kRestOfPart : static_cast<int>(a) - 1;
            }
        f.everywhere.low_s = f.everywhere.high_s = f.everywhere.noise_high_s = f.everywhere.time_s;
    } else if (f.everywhere.status == AreaForecast::Status::forecast) {
        // Never before an area already reached: within the window that holds by itself; one reached
        // after it (ReachedAfterWindow) may come after the forecasts of those still pending.
        for (std::size_t a : everywhere_areas) {
            if (out[a].status != AreaForecast::Status::reached || !(out[a].time_s > f.everywhere.time_s)) continue;
            f.everywhere.time_s = out[a].time_s;
            f.everywhere.low_s = std::max(f.everywhere.low_s, out[a].time_s);
            f.everywhere.high_s = std::max(f.everywhere.high_s, out[a].time_s);
            f.everywhere.noise_high_s = std::max(f.everywhere.noise_high_s, out[a].time_s);
            f.slowest_region = a == rest ? CoverageForecast::kRestOfPart : static_cast<int>(a) - 1;
        }
    }
    f.everywhere.coverage_now = kNaN;
    for (std::size_t a : everywhere_areas)
        f.everywhere.coverage_now =
            std::isnan(f.everywhere.coverage_now) ? out[a].coverage_now : std::min(f.everywhere.coverage_now, out[a].coverage_now);
    f.whole = out[0];
    std::copy(out.begin() + 1, out.begin() + 1 + static_cast<std::ptrdiff_t>(regions), f.regions.begin());
    return f;
}

}  // namespace peensim
