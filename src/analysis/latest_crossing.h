// When the last of several areas reaches the target ("everywhere"): the latest of their crossing
// times, each forecast with its own estimation noise and spread by the run's own noise.
//
// Two things make the latest of several forecasts differ from the latest of the forecasts:
// - The run's own noise. Each area's run crosses at its own time about its forecast (disjoint
//   areas: independently), so when several are close the last of them comes later than the latest
//   forecast: the mean of the latest over draws of them all.
// - The forecasts' own error (the winner's curse). Of areas that will in truth cross together (the
//   20 teeth of a turning gear), the one forecast latest is the one whose estimate came out late by
//   chance: the latest forecast of 20 alike is late by about 1.9 of their standard errors (+7 % on
//   the rotating gear from 60 s, +30 % from 5 s). The correction is that excess, measured by draws
//   of the estimation noise (the jackknife's, with its correlation between areas) about the areas
//   as they would be without it: each area's forecast pulled towards their mean as far as their
//   spread is only noise, among the rivals for the last place only (those within 3 standard errors
//   of the latest forecast; an area truly apart, like a clearly slowest tooth, has no rival and
//   keeps its forecast).
#pragma once

#include <span>
#include <vector>

namespace peensim {

struct AreaCrossing {
    double tau_s = 0.0;               // s, the area's forecast time from the window's end
    double process_sd_s = 0.0;        // s, the run's own noise about it
    std::vector<double> replicate_s;  // s, its jackknife replicates (one per batch left out), in batch order
};

struct LatestCrossing {
    double mean_s = 0.0;             // s, the latest of the areas' crossings: its mean, the chance excess taken off
    double sd_s = 0.0;               // s, its spread from the run's own noise
    double chance_excess_s = 0.0;    // s, what the forecasts' own error adds to their latest (taken off mean_s)
    std::vector<double> last_share;  // per area: the share of the draws in which it came last (without the estimation noise)
};

// areas: every area still to cross (finite tau_s). The excess is computed only when every area has
// as many finite replicates (two or more); else it is 0. Draws from a fixed seed: the same answer
// every time. The noise is drawn in antithetic pairs (+g, -g): an area that is last in every draw
// gets no excess from the draws' own scatter.
LatestCrossing latest_crossing(std::span<const AreaCrossing> areas);

}  // namespace peensim
