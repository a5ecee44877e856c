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
// -(s S1 + s^2 S2 / 2 + s^3 S3 / 3 + ...), S_m = sum_i kappa_i^m, which we take to the third order:
// the estimator exp(-(s S1 + s^2 S2 / 2 + s^3 S3 / 3)) is unbiased to O((s kappa)^4) per impact and,
// unlike the product, never negative. It holds while s kappa stays below 1, so the radius follows
// the extrapolation: h = sqrt(3 s a_q / (pi q)) (a_q the 99th percentile of the dent areas, q =
// kForecastKappaBound), which keeps s kappa <= q for 99 % of the impacts; a point with no impact
// within h keeps its probability 1 (the forecast then never reaches a target that needs it).
//
// Smoothing bias. A kernel of radius h averages the rate over h and so forecasts early where the
// rate varies within h. The forecast is made at h and at 2 h; their difference estimates the bias
// at h (linear in h), and widens the interval's upper end by as much.
//
// Impacts on edges. An impact on an edge or corner of its triangle (the contact point on the edge
// line: a sharp edge of the part, or a facet edge of a curved surface) dents a strip along the
// edge, not the faces around it: spread by the kernel it would cover those faces early. Such
// impacts are left out of the rates: the samples they would cover near the edge are forecast from
// the face impacts alone (late, by 1-2 % on the shipped gear).
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
#include <span>
#include <string>
#include <vector>

#include "analysis/coverage_progress.h"

namespace peensim {

inline constexpr double kForecastKappaBound = 1.0;     // q: s kappa_i stays below it for 99 % of impacts
inline constexpr double kForecastDentQuantile = 0.99;  // the dent area a_q that sets h
inline constexpr double kStartupSigmas = 4.0;          // a first batch this far off the others is a start-up
inline constexpr double kTooShortFactor = 2.0;         // upper end / estimate beyond which no number is given
inline constexpr double kForecastCellsPerRadius = 4.0; // cells of side h / 4 carry the kernel sums

// An impact on a face (not an edge) of the part, in the analysed window.
struct ForecastImpact {
    float point_m[3] = {0, 0, 0};  // m, component frame
    std::uint32_t triangle = 0;    // the mesh triangle it lies on (its normal faces the kernel)
    float dent_area_m2 = 0.0f;     // m2
    std::uint8_t batch = 0;        // the time batch of the window
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
};

// "reached", "forecast", "too_short", "never", "none": as the tables and figures.json name it.
const char* status_name(AreaForecast::Status s);

struct ForecastSummary {
    double radius_m = 0.0;            // h
    double window_s = 0.0;            // the analysed window's length
    double rate_window_s = 0.0;       // the part of it the rates come from (without a start-up batch)
    bool startup_left_out = false;    // the first batch was a start-up transient
    int batches = 0;                  // batches the rates come from
    std::uint64_t face_impacts = 0;   // impacts the rates come from
    std::uint64_t edge_impacts = 0;   // impacts on edges, left out (see above)
    std::size_t cells = 0;            // kernel cells with uncovered area
};

struct CoverageForecast {
    ForecastSummary summary;
    AreaForecast whole;                 // the peened area
    std::vector<AreaForecast> regions;  // per region (RegionSet order); an excluded region: status none
    // Everywhere: every counted region (not excluded, with peened area) at the target, and the
    // rest of the peened area when the regions leave some out (or all of it, without regions);
    // its interval from the jackknife of the slowest area's time (the slowest may change between
    // replicates). coverage_now: the lowest area's.
    AreaForecast everywhere;
    static constexpr int kRestOfPart = -2;  // slowest_region: the peened area in no counted region
    int slowest_region = -1;  // the region that reaches the target last (kRestOfPart; -1: none)
};

// progress: the coverage at the window's end, its dents timed from the window's opening (its target
// is the forecast's); mesh: the part's (component frame); impacts: the face impacts of the window
// (batches in 0 .. batches - 1); window_s (s): its length; edge_impacts: how many were left out on
// edges.
CoverageForecast forecast_coverage(const CoverageProgress& progress, const TriangleMesh& mesh, std::span<const ForecastImpact> impacts,
                                   double window_s, int batches, std::uint64_t edge_impacts);

}  // namespace peensim
