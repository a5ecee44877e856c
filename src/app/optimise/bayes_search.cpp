#include "app/optimise/bayes_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <nlopt.h>

namespace peensim {

namespace {

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }
double normal_pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi); }

// The observations of one model: where, the value, and its runs and their scatter.
struct Observed {
    std::vector<Eigen::VectorXd> u;
    std::vector<double> y, runs, scatter;
    void add(const Eigen::VectorXd& at, double value, double n, double s) {
        u.push_back(at), y.push_back(value), runs.push_back(std::max(1.0, n)), scatter.push_back(s);
    }
};

GaussianProcess fit_on(const Observed& o, int d) {
    const auto n = static_cast<Eigen::Index>(o.u.size());
    GaussianProcess::Data data{Eigen::MatrixXd(n, d), Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd::Zero(n), Eigen::VectorXd(n)};
    for (Eigen::Index i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        data.x.row(i) = o.u[k].transpose();
        data.y(i) = o.y[k];
        data.runs(i) = o.runs[k];
        data.scatter(i) = o.scatter[k];
    }
    return GaussianProcess::fit(data);
}

// What the proposals maximise, for NLopt: -(EI x P(feasible)) at u.
struct Acquisition {
    const SearchModel* model;
    const GaussianProcess* objective;  // the believer's model (with the batch's earlier proposals)
    double best;
    double at(const Eigen::VectorXd& u) const {
        const GpPrediction p = objective->predict(u);
        return expected_improvement(p, best) * model->probability_feasible(u);
    }
};

double negative_acquisition(unsigned n, const double* x, double* gradient, void* data) {
    (void)gradient;
    const Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(x, static_cast<Eigen::Index>(n));
    return -static_cast<const Acquisition*>(data)->at(u);
}

}  // namespace

double expected_improvement(const GpPrediction& p, double best) {
    const double s = std::sqrt(std::max(0.0, p.variance));
    if (s <= 0.0) return std::max(0.0, best - p.mean);
    const double z = (best - p.mean) / s;
    return (best - p.mean) * normal_cdf(z) + s * normal_pdf(z);
}

SearchModel::SearchModel(const std::vector<SearchPoint>& points, std::size_t constraints)
    : objective_(GaussianProcess::with({Eigen::MatrixXd(0, points.empty() ? 1 : points.front().u.size()), Eigen::VectorXd(0),
                                        Eigen::VectorXd(0), Eigen::VectorXd(0), Eigen::VectorXd(0)},
                                       {1.0, std::vector<double>(points.empty() ? 1 : points.front().u.size(), 1.0), 1e-6})) {
    if (points.empty()) return;
    const int d = static_cast<int>(points.front().u.size());
    double worst = -std::numeric_limits<double>::infinity();
    for (const SearchPoint& p : points)
        if (std::isfinite(p.y)) worst = std::max(worst, p.y);
    Observed objective;
    for (const SearchPoint& p : points) {
        if (std::isfinite(p.y))
            objective.add(p.u, p.y, p.runs, p.scatter);
        else if (std::isfinite(worst))
            objective.add(p.u, worst, 1.0, 0.0);
    }
    if (!objective.u.empty()) objective_ = fit_on(objective, d);
    for (std::size_t c = 0; c < constraints; ++c) {
        Observed g;
        for (const SearchPoint& p : points)
            if (c < p.g.size() && std::isfinite(p.g[c])) g.add(p.u, p.g[c], p.runs, c < p.g_scatter.size() ? p.g_scatter[c] : 0.0);
        constraint_fitted_.push_back(!g.u.empty());
        constraints_.push_back(g.u.empty() ? objective_ : fit_on(g, d));
    }
}

double SearchModel::probability_feasible(const Eigen::VectorXd& u) const {
    double p = 1.0;
    for (std::size_t c = 0; c < constraints_.size(); ++c) {
        if (!constraint_fitted_[c]) continue;
        const GpPrediction g = constraints_[c].predict(u);
        const double s = std::sqrt(std::max(0.0, g.variance));
        p *= s > 0.0 ? normal_cdf(-g.mean / s) : (g.mean <= 0.0 ? 1.0 : 0.0);
    }
    return p;
}

std::size_t SearchModel::incumbent(const std::vector<SearchPoint>& points) const {
    std::size_t best = points.size(), most_feasible = 0;
    double best_mean = std::numeric_limits<double>::infinity(), best_p = -1.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const double p = probability_feasible(points[i].u);
        if (p > best_p) best_p = p, most_feasible = i;
        const bool measured_feasible = std::none_of(points[i].g.begin(), points[i].g.end(), [](double g) { return g > 0.0; });
        if (p < kWinnerConfidence || !measured_feasible || !std::isfinite(points[i].y)) continue;
        const double m = objective_.predict(points[i].u).mean;
        if (m < best_mean) best_mean = m, best = i;
    }
    return best < points.size() ? best : most_feasible;
}

std::vector<Eigen::VectorXd> SearchModel::propose(const std::vector<SearchPoint>& points, int count, std::uint64_t seed) const {
    std::vector<Eigen::VectorXd> out;
    if (points.empty() || count < 1) return out;
    const int d = static_cast<int>(points.front().u.size());
    const std::size_t inc = incumbent(points);
    const double best = objective_.predict(points[inc].u).mean;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::normal_distribution<double> step(0.0, 0.05);
    GaussianProcess believer = objective_;
    for (int q = 0; q < count; ++q) {
        const Acquisition acquisition{this, &believer, best};
        // Random starts over the cube and around the incumbent; the best few polished by BOBYQA.
        std::vector<std::pair<double, Eigen::VectorXd>> starts;
        const int random = 500 * d, local = 100 * d;
        for (int k = 0; k < random + local; ++k) {
            Eigen::VectorXd u(d);
            for (int i = 0; i < d; ++i) u(i) = k < random ? uniform(rng) : std::clamp(points[inc].u(i) + step(rng), 0.0, 1.0);
            starts.emplace_back(acquisition.at(u), u);
        }
        std::partial_sort(starts.begin(), starts.begin() + 5, starts.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
        double top = -1.0;
        Eigen::VectorXd chosen = starts.front().second;
        for (int k = 0; k < 5; ++k) {
            std::vector<double> x(starts[static_cast<std::size_t>(k)].second.data(), starts[static_cast<std::size_t>(k)].second.data() + d);
            const std::vector<double> lower(static_cast<std::size_t>(d), 0.0), upper(static_cast<std::size_t>(d), 1.0);
            nlopt_opt opt = nlopt_create(NLOPT_LN_BOBYQA, static_cast<unsigned>(d));
            nlopt_set_lower_bounds(opt, lower.data());
            nlopt_set_upper_bounds(opt, upper.data());
            nlopt_set_min_objective(opt, negative_acquisition, const_cast<Acquisition*>(&acquisition));
            nlopt_set_xtol_rel(opt, 1e-4);
            nlopt_set_maxeval(opt, 200);
            double value = 0.0;
            nlopt_optimize(opt, x.data(), &value);
            nlopt_destroy(opt);
            if (-value > top) top = -value, chosen = Eigen::Map<const Eigen::VectorXd>(x.data(), d);
        }
        if (!(top > 0.0)) {
            // No improvement expected anywhere (the model is sure): the least known feasible place.
            double most = -1.0;
            for (const auto& [unused, u] : starts) {
                (void)unused;
                const double v = believer.predict(u).variance * probability_feasible(u);
                if (v > most) most = v, chosen = u;
            }
        }
        out.push_back(chosen);
        believer = believer.with_observation(chosen, believer.predict(chosen).mean, std::numeric_limits<double>::infinity());
    }
    return out;
}

std::vector<Eigen::VectorXd> latin_hypercube(int n, int d, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::vector<Eigen::VectorXd> best;
    double best_spread = -1.0;
    for (int draw = 0; draw < 50; ++draw) {
        std::vector<Eigen::VectorXd> pts(static_cast<std::size_t>(n), Eigen::VectorXd(d));
        for (int i = 0; i < d; ++i) {
            std::vector<int> strata(static_cast<std::size_t>(n));
            for (int k = 0; k < n; ++k) strata[static_cast<std::size_t>(k)] = k;
            std::shuffle(strata.begin(), strata.end(), rng);
            for (int k = 0; k < n; ++k) pts[static_cast<std::size_t>(k)](i) = (strata[static_cast<std::size_t>(k)] + uniform(rng)) / n;
        }
        double spread = std::numeric_limits<double>::infinity();
        for (std::size_t a = 0; a < pts.size(); ++a)
            for (std::size_t b = a + 1; b < pts.size(); ++b) spread = std::min(spread, (pts[a] - pts[b]).norm());
        if (spread > best_spread) best_spread = spread, best = pts;
    }
    return best;
}

}  // namespace peensim
