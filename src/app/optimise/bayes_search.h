// The optimiser's search (Bayesian optimisation): Gaussian-process models of the objective and of
// each constraint over the evaluated settings, and where to evaluate next: the settings of highest
// expected improvement times the probability that every constraint holds (Gardner et al., ICML
// 2014), a batch at a time by the "kriging believer" (each proposal taken as if it had measured
// the model's own mean there). Settings live in the unit cube [0, 1]^d; the objective is minimised.
// Pure: no runs, no files; the same points and seed give the same proposals.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "app/optimise/gaussian_process.h"

namespace peensim {

// An evaluated setting.
struct SearchPoint {
    Eigen::VectorXd u;     // where, in the unit cube
    double y = 0.0;        // the objective there (to minimise): the mean of its runs; NaN: the evaluation gave none
    double runs = 1.0;     // the runs y averages (its noise: the model's noise of one run / runs)
    double scatter = 0.0;  // the sum of squares of those runs' values about y (runs - 1 degrees of freedom)
    // Each constraint as g <= 0 (scaled: (value - max) / |max|, (min - value) / |min|), the mean of
    // the same runs; NaN: not measured. g_scatter: their sum of squares about it, as `scatter`.
    std::vector<double> g, g_scatter;
};

class SearchModel {
public:
    // Fits the models. A setting without an objective value counts as the worst measured one (so the
    // search leaves its neighbourhood); constraints are fitted on the settings that measured them.
    SearchModel(const std::vector<SearchPoint>& points, std::size_t constraints);

    GpPrediction objective(const Eigen::VectorXd& u) const { return objective_.predict(u); }
    double probability_feasible(const Eigen::VectorXd& u) const;  // of every constraint together (independent models)
    const GaussianProcess& objective_model() const { return objective_; }

    // The evaluated setting the model thinks best: the lowest predicted objective among those whose
    // own runs meet every constraint (on their mean) and whose constraints hold with probability >=
    // kWinnerConfidence in the model (none: the most probably feasible).
    // Index into points. A winner at a constraint's edge with even odds would break it in every
    // other run of the process: a sign-off asks for more.
    static constexpr double kWinnerConfidence = 0.95;
    std::size_t incumbent(const std::vector<SearchPoint>& points) const;

    // `count` settings to evaluate next (the expected improvement over the incumbent's predicted
    // objective times the probability of feasibility, maximised over the cube from random starts
    // and polished by BOBYQA), each later one proposed as if the earlier had measured the model's mean.
    std::vector<Eigen::VectorXd> propose(const std::vector<SearchPoint>& points, int count, std::uint64_t seed) const;

private:
    GaussianProcess objective_;
    std::vector<GaussianProcess> constraints_;
    std::vector<bool> constraint_fitted_;
};

// Expected improvement of a prediction over `best` (minimising): (best - m) Phi(z) + s phi(z), z = (best - m) / s.
double expected_improvement(const GpPrediction& p, double best);

// `n` points of a Latin hypercube in [0, 1]^d (each variable's range cut in n strata, one point in
// each), the most spread of 50 random draws (largest smallest distance).
std::vector<Eigen::VectorXd> latin_hypercube(int n, int d, std::uint64_t seed);

}  // namespace peensim
