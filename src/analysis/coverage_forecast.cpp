#include "analysis/coverage_forecast.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <unordered_map>

#include "analysis/row_runs.h"
#include "analysis/sample_mean.h"
#include "analysis/student_t.h"
#include "analysis/surface_kernel.h"
#include "geometry/mesh_checks.h"

namespace peensim {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kRadiusRounds = 3;         // h is re-chosen at most this often as the extrapolation settles
constexpr double kRadiusSettled = 0.25;  // relative change of the extrapolation below which h stays
constexpr int kRootIterations = 60;      // bisection steps on the span
constexpr double kLargestSpan = 1e6;     // tau / T beyond which a target counts as never reached
constexpr double kRestAreaShare = 1e-6;  // a rest smaller than this share of the peened area is round-off of the regions

// Bins of (cube, facing) keyed into 64 bits: 20 bits per cube coordinate, 3 for the facing.
std::uint64_t cube_key(std::int64_t x, std::int64_t y, std::int64_t z, int facing) {
    const auto axis = [](std::int64_t v) { return static_cast<std::uint64_t>(v) & 0xFFFFF; };
    return axis(x) | axis(y) << 20 | axis(z) << 40 | static_cast<std::uint64_t>(facing + 1) << 60;
}
std::array<std::int64_t, 3> cube_of(const Vec3& p, double inverse_side) {
    return {static_cast<std::int64_t>(std::floor(p.x() * inverse_side)), static_cast<std::int64_t>(std::floor(p.y() * inverse_side)),
            static_cast<std::int64_t>(std::floor(p.z() * inverse_side))};
}

// What an area holds of a cell (m2).
struct AreaTerm {
    std::uint32_t cell = 0;
    double m2 = 0.0;
};

// The surface binned into cells of (cube of side `side`, facing), each with its reachable area,
// that area's first moments, and the uncovered peened area of each class in it.
struct SurfaceCells {
    double side = 0.0;  // m
    std::vector<std::array<std::int64_t, 3>> cube;
    std::vector<int> facing;
    std::vector<double> reach_m2;       // m2
    std::vector<Vec3> point_sum;        // m3: sum of area x position
    std::vector<Vec3> normal_sum;       // m2: sum of area x unit normal
    std::vector<std::pair<std::uint64_t, double>> uncovered;  // (cell << 16 | class, m2), sorted

    SurfaceCells(const CoverageProgress& progress, const TriangleMesh& mesh, double side_m) : side(side_m) {
        const CoverageMap& map = progress.map();
        const SampleClasses& classes = progress.classes();
        const double inverse_side = 1.0 / side;
        std::unordered_map<std::uint64_t, std::uint32_t> cell_of;
        std::unordered_map<std::uint64_t, double> uncovered_of;
        const auto cell_at = [&](const Vec3& p, int face) {
            const std::array<std::int64_t, 3> c = cube_of(p, inverse_side);
            const auto [it, added] = cell_of.try_emplace(cube_key(c[0], c[1], c[2], face), static_cast<std::uint32_t>(reach_m2.size()));
            if (added) {
                cube.push_back(c);
                facing.push_back(face);
                reach_m2.push_back(0.0);
                point_sum.emplace_back(Vec3::Zero());
                normal_sum.emplace_back(Vec3::Zero());
            }
            return it->second;
        };
        map.for_each_sample_row([&](std::size_t t, const Vec3& first, const Vec3& step, std::int64_t count, double area, std::int64_t index) {
            if (classes.reachable_samples(t) == 0) return;
            const Vec3 normal = triangle_normal(mesh, t);
            const int face = facing_of(normal);
            const std::uint16_t uniform = classes.triangle_class(t);
            for_each_cube_run(first, step, count, Vec3::Zero(), inverse_side, [&](std::int64_t i, std::int64_t run) {
                const Vec3 p = first + static_cast<double>(i) * step;
                const std::uint32_t cell = cell_at(p + 0.5 * static_cast<double>(run - 1) * step, face);
                if (uniform != SampleClasses::kMixed) {
                    // The whole run at once: its area, its positions' sum in closed form, its
                    // uncovered samples by a popcount.
                    if (!classes.info(uniform).reachable) return;
                    const double n = static_cast<double>(run);
                    reach_m2[cell] += n * area;
                    point_sum[cell] += area * (n * p + 0.5 * n * (n - 1.0) * step);
                    normal_sum[cell] += n * area * normal;
                    if (!classes.info(uniform).peened()) return;
                    const std::int64_t open = run - map.covered_samples(index + i, run);
                    if (open > 0) uncovered_of[static_cast<std::uint64_t>(cell) << 16 | uniform] += static_cast<double>(open) * area;
                    return;
                }
                for (std::int64_t j = i; j < i + run; ++j) {
                    const std::uint16_t k = classes.class_of(t, index + j);
                    if (!classes.info(k).reachable) continue;
                    reach_m2[cell] += area;
                    point_sum[cell] += area * (first + static_cast<double>(j) * step);
                    normal_sum[cell] += area * normal;
                    if (classes.info(k).peened() && !map.covered(index + j)) uncovered_of[static_cast<std::uint64_t>(cell) << 16 | k] += area;
                }
            });
        });
        uncovered.assign(uncovered_of.begin(), uncovered_of.end());
        std::sort(uncovered.begin(), uncovered.end());
    }
};

// The kernel sums of one radius h over the surface's cells of side h / kForecastCellsPerRadius, and
// the spans they forecast.
class KernelField {
public:
    KernelField(const CoverageProgress& progress, const TriangleMesh& mesh, std::span<const ForecastImpact> impacts, int batches,
                const std::vector<bool>& batch_used, double radius_m, const std::vector<std::vector<std::uint32_t>>& areas_of_class,
                std::size_t area_count)
        : batches_(batches), batch_used_(batch_used), radius_(radius_m) {
        adopt(SurfaceCells(progress, mesh, radius_m / kForecastCellsPerRadius), areas_of_class, area_count);
        build_neighbours();
        sum_kernels(mesh, impacts);
    }

    std::size_t uncovered_cells() const { return uncovered_cells_; }

    // tau / T_rate (the extrapolation span) at which area a's uncovered area falls to remaining_m2,
    // from the batches in use but `left_out` (-1: none); +inf: never; 0: already.
    double span_to(std::size_t a, double remaining_m2, int left_out) const {
        const std::vector<AreaTerm>& terms = terms_[a];
        moments_.resize(terms.size());
        double never = 0.0, now = 0.0;  // m2: uncovered with no impact within h; uncovered now
        for (std::size_t k = 0; k < terms.size(); ++k) {
            const std::size_t c = terms[k].cell;
            double m[3] = {0, 0, 0};
            for (int b = 0; b < batches_; ++b) {
                if (!batch_used_[static_cast<std::size_t>(b)] || b == left_out) continue;
                const double* s = &sums_[(c * static_cast<std::size_t>(batches_) + static_cast<std::size_t>(b)) * 3];
                m[0] += s[0], m[1] += s[1], m[2] += s[2];
            }
            const double inv = norm_[c] > 0.0 ? 1.0 / norm_[c] : 0.0;
            // The exponent's series: s S1 + s^2 S2 / 2 + s^3 S3 / 3, S_m = sum kappa^m.
            moments_[k] = {m[0] * inv, 0.5 * m[1] * inv * inv, m[2] * inv * inv * inv / 3.0};
            now += terms[k].m2;
            if (!(moments_[k][0] > 0.0)) never += terms[k].m2;
        }
        if (now <= remaining_m2) return 0.0;
        if (never >= remaining_m2) return kInf;
        const auto uncovered = [&](double s) {
            double u = 0.0;
            for (std::size_t k = 0; k < terms.size(); ++k) {
                const auto& m = moments_[k];
                u += terms[k].m2 * std::exp(-s * (m[0] + s * (m[1] + s * m[2])));
            }
            return u;
        };
        double lo = 0.0, hi = 1.0;
        while (uncovered(hi) > remaining_m2) {
            lo = hi;
            hi *= 2.0;
            if (hi > kLargestSpan) return kInf;
        }
        for (int i = 0; i < kRootIterations && hi - lo > 1e-9 * hi; ++i) {
            const double mid = lo > 0.0 ? std::sqrt(lo * hi) : 0.5 * hi;
            (uncovered(mid) > remaining_m2 ? lo : hi) = mid;
        }
        return 0.5 * (lo + hi);
    }

private:
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
        std::sort(keyed.begin(), keyed.end());
        grid_cells_.resize(keyed.size());
        for (std::size_t i = 0; i < keyed.size(); ++i) {
            grid_cells_[i] = keyed[i].second;
            auto [it, added] = grid_.try_emplace(keyed[i].first, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i));
            it->second.second = static_cast<std::uint32_t>(i + 1);
        }
    }

    template <class Visit>
    void for_each_cell_near(const Vec3& p, Visit&& visit) const {
        const double r2 = radius_ * radius_;
        const auto q = cube_of(p, 1.0 / radius_);
        for (std::int64_t dz = -1; dz <= 1; ++dz)
            for (std::int64_t dy = -1; dy <= 1; ++dy)
                for (std::int64_t dx = -1; dx <= 1; ++dx) {
                    const auto it = grid_.find(cube_key(q[0] + dx, q[1] + dy, q[2] + dz, -1));
                    if (it == grid_.end()) continue;
                    for (std::uint32_t i = it->second.first; i < it->second.second; ++i) {
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
        sums_.assign(cells * static_cast<std::size_t>(batches_) * 3, 0.0);
        for (const ForecastImpact& i : impacts) {
            const Vec3 p(i.point_m[0], i.point_m[1], i.point_m[2]);
            const Vec3 n = triangle_normal(mesh, i.triangle);
            const double a = i.dent_area_m2;
            for_each_cell_near(p, [&](std::uint32_t c, double d2) {
                if (!uncovered_cell_[c]) return;
                const double w = quartic(d2, inv_r2) * std::max(0.0, normal_[c].dot(n)) * a;
                if (!(w > 0.0)) return;
                double* s = &sums_[(c * static_cast<std::size_t>(batches_) + i.batch) * 3];
                s[0] += w, s[1] += w * w, s[2] += w * w * w;
            });
        }
    }

    int batches_;
    std::vector<bool> batch_used_;
    double radius_;
    // Cells (structure of arrays).
    std::vector<double> reach_m2_;  // m2: reachable area
    std::vector<Vec3> centroid_;    // m
    std::vector<Vec3> normal_;      // unit
    std::vector<bool> uncovered_cell_;
    std::vector<double> norm_;  // m2: sum_q w A_q
    std::vector<double> sums_;  // per cell, batch: sum of w a, (w a)^2, (w a)^3 (m2, m4, m6)
    std::vector<std::vector<AreaTerm>> terms_;  // per area: its cells' uncovered area
    std::size_t uncovered_cells_ = 0;
    std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> grid_;
    std::vector<std::uint32_t> grid_cells_;
    mutable std::vector<std::array<double, 3>> moments_;  // scratch of span_to
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

// The radius that keeps s kappa <= q for the dent area a_q at span s (see the header).
double radius_for(double span, double dent_area_q) { return std::sqrt(3.0 * span * dent_area_q / (M_PI * kForecastKappaBound)); }

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
                                   double window_s, int batches, std::uint64_t edge_impacts) {
    const SampleClasses& classes = progress.classes();
    const double target = progress.target();
    const std::size_t regions = classes.region_count();
    const std::size_t areas = regions + 2;  // 0: the peened area, 1 + r: region r, last: the rest
    const std::size_t rest = areas - 1;
    CoverageForecast f;
    f.summary.window_s = window_s;
    f.summary.edge_impacts = edge_impacts;
    f.summary.face_impacts = impacts.size();
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

        // The first extrapolation span: as if each area's rate were even (C = 1 - exp(-k t)), doubled.
        double span = 0.0;
        for (std::size_t a = 0; a < areas; ++a) {
            if (!pending(a)) continue;
            const double c = std::clamp(out[a].coverage_now, 1e-9, target);
            span = std::max(span, 2.0 * std::log((1.0 - c) / (1.0 - target)) / -std::log1p(-c));
        }
        span = std::clamp(span, 0.1, kLargestSpan);
        const auto remaining = [&](std::size_t a) { return (1.0 - target) * area_m2[a]; };

        std::vector<double> spans(areas, kNaN);
        double radius = radius_for(span, dent_q);
        for (int round = 0; round < kRadiusRounds; ++round) {
            radius = radius_for(span, dent_q);
            const KernelField field(progress, mesh, impacts, batches, used, radius, areas_of_class, areas);
            f.summary.cells = field.uncovered_cells();
            double slowest = 0.0;
            for (std::size_t a = 0; a < areas; ++a) {
                if (!pending(a)) continue;
                spans[a] = field.span_to(a, remaining(a), -1);
                if (std::isfinite(spans[a])) slowest = std::max(slowest, spans[a]);
            }
            const bool settled = slowest > 0.0 && std::abs(slowest - span) <= kRadiusSettled * span;
            if (slowest > 0.0) span = slowest;
            if (!settled && round < kRadiusRounds - 1) continue;

            // The jackknife at h (each used batch left out in turn: the rate window shrinks with
            // it), and the smoothing bias from 2 h.
            const KernelField wide(progress, mesh, impacts, batches, used, 2.0 * radius, areas_of_class, areas);
            const double quantile = student_t_two_sided_quantile(0.05, std::max(1.0, used_count - 1.0));
            const double left_out_window = rate_window * (used_count - 1) / std::max(1, used_count);
            std::vector<std::vector<double>> replicate(areas);  // per area: tau of each replicate (s)
            for (std::size_t a = 0; a < areas; ++a) {
                if (!pending(a) || !std::isfinite(spans[a])) continue;
                for (int b = 0; b < batches; ++b)
                    if (used[static_cast<std::size_t>(b)]) replicate[a].push_back(field.span_to(a, remaining(a), b) * left_out_window);
            }
            const auto finish = [&](AreaForecast& o, double tau, const std::vector<double>& taus, double wide_tau) {
                if (!std::isfinite(tau)) {
                    o.status = AreaForecast::Status::never;
                    o.time_s = o.low_s = o.high_s = o.noise_high_s = kInf;
                    return;
                }
                const double se = jackknife_se(taus);
                o.time_s = window_s + tau;
                o.low_s = window_s + tau * std::exp(-quantile * se);
                o.noise_high_s = std::isfinite(se) ? window_s + tau * std::exp(quantile * se) : kInf;
                o.bias_s = std::isfinite(wide_tau) ? std::max(0.0, tau - wide_tau) : 0.0;
                o.high_s = o.noise_high_s + o.bias_s;
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
                finish(out[a], spans[a] * rate_window, replicate[a], wide.span_to(a, remaining(a), -1) * rate_window);
            }
            // Everywhere: the slowest counted area, in every replicate.
            if (!everywhere_areas.empty()) {
                double tau = -kInf, wide_tau = -kInf;
                std::vector<double> taus(replicate[everywhere_areas.front()].size(), -kInf);
                bool any = false;
                for (std::size_t a : everywhere_areas) {
                    if (!pending(a)) continue;
                    any = true;
                    if (spans[a] * rate_window > tau) {
                        tau = spans[a] * rate_window;
                        f.slowest_region = a == rest ? CoverageForecast::kRestOfPart : static_cast<int>(a) - 1;
                    }
                    wide_tau = std::max(wide_tau, wide.span_to(a, remaining(a), -1) * rate_window);
                    taus.resize(std::max(taus.size(), replicate[a].size()), -kInf);
                    for (std::size_t k = 0; k < replicate[a].size(); ++k) taus[k] = std::max(taus[k], replicate[a][k]);
                    if (!std::isfinite(spans[a])) taus.assign(taus.size(), kInf);
                }
                if (any) finish(f.everywhere, tau, taus, wide_tau);
            }
            break;
        }
        f.summary.radius_m = radius;
    }
    // Everywhere already reached: when its last area did.
    if (f.everywhere.status == AreaForecast::Status::none && !everywhere_areas.empty() &&
        std::all_of(everywhere_areas.begin(), everywhere_areas.end(), [&](std::size_t a) { return out[a].status == AreaForecast::Status::reached; })) {
        f.everywhere.status = AreaForecast::Status::reached;
        f.everywhere.time_s = 0.0;
        for (std::size_t a : everywhere_areas)
            if (out[a].time_s >= f.everywhere.time_s) {
                f.everywhere.time_s = out[a].time_s;
                f.slowest_region = a == rest ? CoverageForecast::kRestOfPart : static_cast<int>(a) - 1;
            }
        f.everywhere.low_s = f.everywhere.high_s = f.everywhere.noise_high_s = f.everywhere.time_s;
    }
    f.everywhere.coverage_now = kNaN;
    for (std::size_t a : everywhere_areas)
        f.everywhere.coverage_now = std::isnan(f.everywhere.coverage_now) ? out[a].coverage_now : std::min(f.everywhere.coverage_now, out[a].coverage_now);
    f.whole = out[0];
    std::copy(out.begin() + 1, out.begin() + 1 + static_cast<std::ptrdiff_t>(regions), f.regions.begin());
    return f;
}

}  // namespace peensim
