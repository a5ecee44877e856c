// How long until coverage reaches a target, forecast from where the dents land, point by point.
//
// The model (SAE J2277's, the Boolean model). Dents land at random; a point x of the surface is
// covered by dents arriving at a rate mu(x) (dents per second whose disc holds x), so once it is
// still uncovered at the end T of the analysed window it stays so until T + tau with probability
// exp(-mu(x) tau). The uncovered share of an area at T + tau is the sum of that over its uncovered
// samples now; the time to the target is where it falls to 1 - target. Nothing assumes that the
// rate is even over the area: the least-hit points, which decide the time to 98 %, count as they
// are. (One Avrami constant per region assumes an even rate and came out 2-3x short on the shipped
// gears.)
//
// The rate. mu(x) is the dent area per unit area delivered around x: the impacts' dent areas a_i
// spread by the quartic kernel of support h with the facing factor (surface_kernel.h), over the
// reachable area around x, kappa_i(x) = w(x, x_i) a_i / sum_p w(x, x_p) A_p (so that sum_i kappa_i
// / T estimates mu smoothed over h). A finite run knows mu only through these counts, and the
// naive plug-in exp(-tau sum kappa_i / T) is biased late (counting noise widens the spread of rates
// it sees, and exp is convex). Because the impacts form a Poisson process, prod_i (1 - s kappa_i),
// s = tau / T, is an unbiased estimator of exp(-tau mu_h(x)); its logarithm is the series
// -(s S1 + s^2 S2 / 2 + s^3 S3 / 3 + ...), S_m = sum_i kappa_i^m, which we take to the sixth order:
// the estimator exp(-sum_(m <= 6) s^m S_m / m) is unbiased to O((s kappa)^7) per impact and,
// unlike the product, never negative. It holds while s kappa stays below 1, so the radius follows
// the extrapolation: h = sqrt(3 s a_q / (pi q)) (a_q the 99th percentile of the dent areas, q =
// kForecastKappaBound), which keeps s kappa <= q for 99 % of the impacts, and never less than
// kHoleMargin dent radii of a_q (an uncovered point has no impact within its dent radius: a run
// near its target, forecasting a short way, would otherwise see none and say "never"); a point
// with no impact within h keeps its probability 1 (the forecast then never reaches a target that
// needs it).
//
// Smoothing bias. A kernel of radius h averages the rate over h and so forecasts early where the
// rate varies within h (structure at h's own scale is not seen at all: bands of the rate as wide as
// h came out 28 % early, outside the interval; a run 4x longer, whose h is half, held them). The
// forecast is made at h and at 2 h; their difference estimates the bias at h (linear in h: the
// rate jumps at edges and between faces) and corrects the forecast; the interval runs from the
// uncorrected lower end to the corrected upper end, and when the wider kernel forecasts later (the field is not smooth at h's scale: the
// part has features about h across) the upper end reaches that forecast too.
//
// The selection of the uncovered. A sample still uncovered has no impact within its dent radius
// (that is why it is uncovered), so the impacts around it are fewer than the kernel expects by the
// kernel's mass over that hole: each impact's kappa is divided by the kernel's integral less its
// own hole (along an edge line: its chord). Without it a 60 s run of a part 97 % covered forecast
// its last 3 % 20 % late.
//
// The reach boundary. A dent is centred where a shot touched, so a sample within a dent radius of
// the samples no shot can reach (a bore an axle fills, a root fillet narrower than the shot) is
// covered only by the dents on its own side: each impact's kappa there is multiplied by the share
// of its dent's disc on the reachable side of the boundary (reach_boundary.h), per band of distance
// (kReachBands per largest dent radius). On a cube in reachable strips 0.5 mm wide (dents 0.25 mm)
// the whole disc made the forecast 8 % early; the share puts it 1 % late (the gear's axle ring
// and roots: the whole-part forecast 0.2-0.3 % later).
//
// The run's own noise. The forecast is the expected uncovered area; the run it is checked against
// is one draw of the dents to come. For a Boolean model of dents of area a the variance of the
// uncovered area follows from the dents that would cover two points at once (their overlap share
// g(r)); summed over the uncovered samples and divided by the slope of the uncovered area, it gives
// the spread of the crossing time, added to the jackknife's. "Everywhere" is the last of its areas
// to cross: with their spreads, the mean of the latest of them (a few close areas: later than the
// latest forecast).
//
// Impacts on edges. An impact on an edge or corner of its triangle (the contact point on the edge
// line: a sharp edge of the part, or a facet edge of a curved surface, where a sphere touches a
// convex polyhedron over a whole wedge of directions) dents only the strip within its dent radius
// of that line: 28 % of the shipped gear's impacts, 22 % of a 96-sided shaft's. Spread over the
// faces by the areal kernel they would cover the faces' middles early; left out, they would leave
// the strips, which on a finely faceted surface are much of it, late (+5-7 % on the shaft). They
// are a line process of their own: per edge line, the impacts' density along it is smoothed by the
// 1D quartic kernel (truncated at the line's ends and renormalised), and across it
// the footprint is exact: a dent of radius rho at distance d covers a chord 2 sqrt(rho^2 - d^2) of
// the line, so kappa_j(x) = K(s_x - s_j) 2 sqrt(rho_j^2 - d_x^2), and the 1D kernel's radius keeps
// s kappa <= q as h does for the areal one (15 s rho_q / (8 q), at least h). The samples within the largest
// dent radius of a line with impacts are grouped by cell, class, line and a band of distance
// (kEdgeBands per radius) and take these sums on top of their cell's areal ones.
//
// The interval. The time batches of the window are nearly independent: a delete-one-batch
// jackknife of log(tau) gives its standard error, the interval tau exp(+- t(0.975, B - 1) se), then
// widened by the smoothing bias. A start-up batch (the first, when its dent-area rate lies more
// than kStartupSigmas standard errors from the others': the load lifting off the sonotrode) is left
// out of the rates.
//
// Too short to say. The forecast is no number when the interval's upper end exceeds
// kTooShortFactor times the estimate, or no upper end exists; it then gives the run length at
// which it would (the noise falls as 1 / sqrt(T), the smoothing bias as h ~ sqrt(tau / T)).
//
// Pure computation: no file I/O, no printing.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "analysis/coverage_progress.h"

namespace peensim {

inline constexpr double kForecastKappaBound = 0.5;     // q: s kappa_i stays below it for 99 % of impacts
inline constexpr double kForecastDentQuantile = 0.99;  // the dent area a_q that sets h
inline constexpr double kStartupSigmas = 4.0;          // a first batch this far off the others is a start-up
// A line through the used batches' dent areas whose slope is this many of its standard errors from
// flat: the rate drifts within the window (a load that grows or settles), which the forecast, taking
// the window's mean rate for all time to come, does not model; the report says so.
inline constexpr double kDriftSigmas = 4.0;
inline constexpr double kTooShortFactor = 2.0;          // upper end / estimate beyond which no number is given
inline constexpr double kForecastCellsPerRadius = 4.0;  // cells of side h / 4 carry the kernel sums
inline constexpr int kEdgeBands = 8;                    // bands of distance to an edge line per largest dent radius
inline constexpr double kHoleMargin = 2.0;              // h is at least this many dent radii of a_q

// An impact of the part in the analysed window.
struct ForecastImpact {
    float point_m[3] = {0, 0, 0};  // m, component frame
    std::uint32_t triangle = 0;    // the mesh triangle it lies on (its normal faces the kernel)
    float dent_area_m2 = 0.0f;     // m2
    std::uint8_t batch = 0;        // the time batch of the window
    std::int8_t edge = -1;         // the edge of its triangle it lies on (mesh_checks.h: triangle_edge_at), -1: a face
};

// The forecast for one area (the whole peened area, or a region).
struct AreaForecast {
    enum class Status {
        reached,    // the target is reached within the window: reached_at_s
        forecast,   // time_s with its interval
        too_short,  // the interval is too wide to act on: run_for_s says how long a run would tell
        never,      // part of the area has no impact within h: at this rate it is never covered
        none,       // no peened area, or no impact at all
    };
    Status status = Status::none;
    double coverage_now = 0.0;  // 0..1
    double time_s = 0.0;        // s since the window opened (forecast; also too_short, for reference)
    double low_s = 0.0;         // s, 95 % interval
    double high_s = 0.0;        // s (infinity: no upper end)
    double noise_high_s = 0.0;  // s, the interval's upper end before the smoothing bias was added
    double bias_s = 0.0;        // s, the smoothing bias allowance (forecast at h minus at 2 h, >= 0)
    double run_for_s = 0.0;     // s, too_short: a window this long would give a number
    // reached after the window's end, at a time the caller knew (ReachedAfterWindow below: a run
    // until coverage that counted this area's dents past the last whole turn the window ends at);
    // coverage_now is still the window's.
    bool seen_in_run = false;
};

// "reached", "forecast", "too_short", "never", "none": as the tables and figures.json name it.
const char* status_name(AreaForecast::Status s);

struct ForecastSummary {
    double radius_m = 0.0;          // h
    double window_s = 0.0;          // the analysed window's length
    double rate_window_s = 0.0;     // the part of it the rates come from (without a start-up batch)
    bool startup_left_out = false;  // the first batch was a start-up transient
    // -, the impact (dent area) rate's fitted change from the first used batch to the last, over its
    // mean; `rate_drifts`: that slope stands kDriftSigmas standard errors from flat.
    double rate_change = 0.0;
    bool rate_drifts = false;
    int batches = 0;                 // batches the rates come from
    std::uint64_t face_impacts = 0;  // impacts on faces (the areal rates)
    std::uint64_t edge_impacts = 0;  // impacts on edges (the rates along edge lines, see above)
    std::size_t edge_lines = 0;      // edge lines with impacts
    std::size_t cells = 0;           // kernel cells with uncovered area
    // s, what the areas' forecasts' own error added to the latest of them, taken off everywhere's
    // time (latest_crossing.h: the winner's curse of areas alike).
    double everywhere_chance_excess_s = 0.0;
};

struct CoverageForecast {
    ForecastSummary summary;
    AreaForecast whole;                 // the peened area
    std::vector<AreaForecast> regions;  // per region (RegionSet order); an excluded region: status none
    // Everywhere: every counted region (not excluded, with peened area) at the target, and the
    // rest of the peened area when the regions leave some out (or all of it, without regions):
    // the latest of their crossings (latest_crossing.h), which may come before the latest of their
    // forecasts when several are alike; its interval from the jackknife of the slowest area's time
    // (the slowest may change between replicates), its upper end never below any area's.
    // coverage_now: the lowest area's.
    AreaForecast everywhere;
    static constexpr int kRestOfPart = -2;  // slowest_region: the peened area in no counted region
    int slowest_region = -1;                // the region that reaches the target last (kRestOfPart; -1: none)
};

// Areas that reached the target after the window's end, when the caller knows it (s since the
// window opened; NaN: not known): the peened area, and per region (empty: none). Such an area is
// reached then, not forecast, and everywhere is no earlier.
struct ReachedAfterWindow {
    double whole_s = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> region_s;
};

// progress: the coverage at the window's end, its dents timed from the window's opening (its target
// is the forecast's); mesh: the part's (component frame); impacts: those of the window on faces and
// edges (batches in 0 .. batches - 1); window_s (s): its length.
CoverageForecast forecast_coverage(const CoverageProgress& progress, const TriangleMesh& mesh, std::span<const ForecastImpact> impacts,
                                   double window_s, int batches, const ReachedAfterWindow& later = {});

}  // namespace peensim
