#include "analysis/latest_crossing.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace peensim {

namespace {

constexpr int kDraws = 4000;
constexpr std::uint64_t kSeed = 20261127;
constexpr double kRivalSigmas = 3.0;  // an area this many standard errors of the difference below the latest forecast cannot be last

// The estimation noise of the areas' log forecasts, from their jackknife replicates: per area the
// replicates' deviations from their mean, scaled so that sum_k g_k dev[a][k] (g_k standard normal)
// has the jackknife's variance, and the covariance between areas the replicates show. A draw
// scales the area's forecast by 1 + that sum (not its exponential: the excess measured is the
// latest's, not the log-normal's own mean shift).
struct EstimationNoise {
    std::vector<std::vector<double>> dev;  // [area][replicate]
    bool usable = false;
};

EstimationNoise estimation_noise(std::span<const AreaCrossing> areas) {
    EstimationNoise e;
    const std::size_t replicates = areas.front().replicate_s.size();
    if (areas.size() < 2 || replicates < 2) return e;
    const double r = static_cast<double>(replicates);
    for (const AreaCrossing& a : areas) {
        if (a.replicate_s.size() != replicates || !(a.tau_s > 0.0)) return e;
        std::vector<double> logs;
        for (double t : a.replicate_s) {
            if (!std::isfinite(t) || !(t > 0.0)) return e;
            logs.push_back(std::log(t));
        }
        double mean = 0.0;
        for (double l : logs) mean += l / r;
        for (double& l : logs) l = (l - mean) * std::sqrt((r - 1.0) / r);
        e.dev.push_back(std::move(logs));
    }
    e.usable = true;
    return e;
}

// The areas' log forecasts as they would be without their estimation noise: pulled towards their
// mean by the share of their spread that the noise accounts for (a normal random-effects model,
// its between-area variance by moments). The common noise of all areas (a batch that was rich
// everywhere) moves the mean, not the spread, so the spread's noise is taken on deviations from
// the mean replicate by replicate.
std::vector<double> without_noise(std::span<const AreaCrossing> areas, const EstimationNoise& noise) {
    const std::size_t n = areas.size(), replicates = noise.dev.front().size();
    std::vector<double> y(n);
    double mean = 0.0;
    for (std::size_t a = 0; a < n; ++a) y[a] = std::log(areas[a].tau_s), mean += y[a] / static_cast<double>(n);
    std::vector<double> common(replicates, 0.0);  // the replicates' mean deviation over the areas
    for (std::size_t a = 0; a < n; ++a)
        for (std::size_t k = 0; k < replicates; ++k) common[k] += noise.dev[a][k] / static_cast<double>(n);
    std::vector<double> own(n, 0.0);  // each area's noise variance about the areas' mean
    double spread = 0.0, mean_own = 0.0;
    for (std::size_t a = 0; a < n; ++a) {
        for (std::size_t k = 0; k < replicates; ++k) own[a] += std::pow(noise.dev[a][k] - common[k], 2);
        spread += std::pow(y[a] - mean, 2) / static_cast<double>(n - 1);
        mean_own += own[a] / static_cast<double>(n);
    }
    const double between = std::max(0.0, spread - mean_own);
    for (std::size_t a = 0; a < n; ++a) {
        const double keep = own[a] > 0.0 ? between / (between + own[a]) : 1.0;
        y[a] = mean + keep * (y[a] - mean);
    }
    return y;
}

// The areas that may be the last: those whose forecast lies within kRivalSigmas standard errors
// of the difference (from the replicates: their correlation counted) of the latest forecast. Only
// among them is the chance excess measured: an area far behind says nothing about how alike the
// rivals are (pooled with them, a clearly slowest area would be pulled into the pack).
std::vector<std::size_t> rivals(std::span<const AreaCrossing> areas, const EstimationNoise& noise) {
    std::size_t top = 0;
    for (std::size_t a = 1; a < areas.size(); ++a)
        if (areas[a].tau_s > areas[top].tau_s) top = a;
    std::vector<std::size_t> out;
    for (std::size_t a = 0; a < areas.size(); ++a) {
        double variance = 0.0;
        for (std::size_t k = 0; k < noise.dev[a].size(); ++k) variance += std::pow(noise.dev[a][k] - noise.dev[top][k], 2);
        if (a == top || std::log(areas[top].tau_s / areas[a].tau_s) <= kRivalSigmas * std::sqrt(variance)) out.push_back(a);
    }
    return out;
}

}  // namespace

LatestCrossing latest_crossing(std::span<const AreaCrossing> areas) {
    LatestCrossing out;
    if (areas.empty()) return out;
    if (areas.size() == 1) return {areas[0].tau_s, areas[0].process_sd_s, 0.0, {1.0}};  // the one area: its own
    EstimationNoise noise = estimation_noise(areas);
    // The rivals for the last place, their noise and their forecasts as they would be without it.
    std::vector<std::size_t> rival;
    std::vector<double> settled;
    if (noise.usable) {
        rival = rivals(areas, noise);
        std::vector<AreaCrossing> rival_areas;
        EstimationNoise rival_noise;
        rival_noise.usable = true;
        for (std::size_t a : rival) rival_areas.push_back(areas[a]), rival_noise.dev.push_back(noise.dev[a]);
        noise = std::move(rival_noise);
        if (rival.size() >= 2)
            settled = without_noise(rival_areas, noise);
        else
            noise.usable = false;  // one rival: nothing to take off
    }
    std::mt19937_64 rng(kSeed);
    std::normal_distribution<double> normal(0.0, 1.0);
    const std::size_t replicates = noise.usable ? noise.dev.front().size() : 0;
    std::vector<double> g(replicates), run_noise(areas.size()), e(areas.size(), 0.0);
    out.last_share.assign(areas.size(), 0.0);
    double sum = 0.0, sum2 = 0.0, excess = 0.0;
    for (int d = 0; d < kDraws; ++d) {
        for (double& v : g) v = normal(rng);
        double last = -std::numeric_limits<double>::infinity(), last_settled = last;
        std::size_t last_area = 0;
        for (std::size_t a = 0; a < areas.size(); ++a) {
            run_noise[a] = areas[a].process_sd_s * normal(rng);
            if (areas[a].tau_s + run_noise[a] > last) last = areas[a].tau_s + run_noise[a], last_area = a;
        }
        sum += last, sum2 += last * last;
        out.last_share[last_area] += 1.0 / kDraws;
        if (!noise.usable) continue;
        for (std::size_t r = 0; r < rival.size(); ++r) {
            e[r] = 0.0;
            for (std::size_t k = 0; k < replicates; ++k) e[r] += g[k] * noise.dev[r][k];
            last_settled = std::max(last_settled, std::exp(settled[r]) + run_noise[rival[r]]);
        }
        for (const double sign : {1.0, -1.0}) {
            double last_noisy = -std::numeric_limits<double>::infinity();
            for (std::size_t r = 0; r < rival.size(); ++r)
                last_noisy = std::max(last_noisy, std::exp(settled[r]) * (1.0 + sign * e[r]) + run_noise[rival[r]]);
            excess += 0.5 * (last_noisy - last_settled) / kDraws;
        }
    }
    const double mean = sum / kDraws;
    out.sd_s = std::sqrt(std::max(0.0, sum2 / kDraws - mean * mean));
    out.chance_excess_s = excess;
    out.mean_s = mean - excess;
    return out;
}

}  // namespace peensim
