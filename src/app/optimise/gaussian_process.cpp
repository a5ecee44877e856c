#include "app/optimise/gaussian_process.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include <nlopt.h>

namespace peensim {

namespace {

// The hyperparameters' search box, for the standardised figure on the unit cube: a length from a
// twentieth of the range (a sharp valley) to five ranges (nearly linear); a signal from a tenth to
// ten times the data's variance; one run's noise from nothing to a hundred times the data's
// variance (the data are means of runs: a flat truth seen through 4 runs a setting has a run
// variance 4 times its means').
constexpr double kMinLength = 0.05, kMaxLength = 5.0;
constexpr double kMinSignal = 0.1, kMaxSignal = 10.0;
constexpr double kMinNugget = 1e-6, kMaxNugget = 100.0;

// theta = (log signal, log length_1..d, log nugget) <-> hyperparameters.
GpHyperparameters from_theta(const double* theta, int d) {
    GpHyperparameters h;
    h.signal_variance = std::exp(theta[0]);
    for (int i = 0; i < d; ++i) h.length.push_back(std::exp(theta[1 + i]));
    h.nugget = std::exp(theta[1 + d]);
    return h;
}

struct FitData {
    const GaussianProcess::Data* data;
    int d;
};

double negative_log_likelihood(unsigned n, const double* theta, double* gradient, void* data) {
    (void)n;
    (void)gradient;  // BOBYQA is derivative-free
    const auto* f = static_cast<const FitData*>(data);
    const GpHyperparameters h = from_theta(theta, f->d);
    const GaussianProcess gp = GaussianProcess::with(*f->data, h);
    double l = gp.log_marginal_likelihood();
    for (const double length : h.length) l += 2.0 * std::log(length) - 6.0 * length;  // Gamma(3, 6), up to a constant
    return std::isfinite(l) ? -l : 1e300;
}

}  // namespace

double matern52(double r) {
    const double s = std::sqrt(5.0) * r;
    return (1.0 + s + s * s / 3.0) * std::exp(-s);
}

GaussianProcess::GaussianProcess(Data data, const GpHyperparameters& h, double y_mean, double y_scale)
    : d_(std::move(data)), h_(h), y_mean_(y_mean), y_scale_(y_scale) {
    const Eigen::Index n = d_.x.rows();
    if (d_.y.size() != n || d_.runs.size() != n || d_.known_variance.size() != n || d_.scatter.size() != n ||
        static_cast<Eigen::Index>(h_.length.size()) != d_.x.cols())
        throw std::invalid_argument("GaussianProcess: the observations' sizes differ");
    Eigen::MatrixXd k(n, n);
    for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j <= i; ++j) k(i, j) = k(j, i) = kernel(d_.x.row(i).transpose(), d_.x.row(j).transpose());
    for (Eigen::Index i = 0; i < n; ++i) k(i, i) += h_.nugget / d_.runs(i) + d_.known_variance(i) / (y_scale_ * y_scale_);
    const Eigen::VectorXd z = (d_.y.array() - y_mean_) / y_scale_;
    // A tiny jitter if rounding left the matrix short of positive definite (coincident points).
    for (double jitter = 0.0; jitter < 1e-2; jitter = jitter == 0.0 ? 1e-10 : jitter * 100.0) {
        llt_.compute(k + jitter * Eigen::MatrixXd::Identity(n, n));
        if (llt_.info() == Eigen::Success) break;
    }
    if (llt_.info() != Eigen::Success) {
        log_likelihood_ = -std::numeric_limits<double>::infinity();
        alpha_ = Eigen::VectorXd::Zero(n);
        return;
    }
    alpha_ = llt_.solve(z);
    const Eigen::MatrixXd l = llt_.matrixL();
    log_likelihood_ =
        -0.5 * z.dot(alpha_) - l.diagonal().array().log().sum() - 0.5 * static_cast<double>(n) * std::log(2.0 * std::numbers::pi);
    // The runs about their means: independent of the means, normal with the noise of one run.
    const double run_variance = h_.nugget * y_scale_ * y_scale_;
    for (Eigen::Index i = 0; i < n; ++i) {
        const double dof = d_.runs(i) - 1.0;
        if (dof >= 1.0 && std::isfinite(dof))
            log_likelihood_ -= 0.5 * dof * std::log(2.0 * std::numbers::pi * run_variance) + 0.5 * d_.scatter(i) / run_variance;
    }
}

double GaussianProcess::kernel(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
    double r2 = 0.0;
    for (Eigen::Index i = 0; i < a.size(); ++i) {
        const double t = (a(i) - b(i)) / h_.length[static_cast<std::size_t>(i)];
        r2 += t * t;
    }
    return h_.signal_variance * matern52(std::sqrt(r2));
}

GaussianProcess GaussianProcess::with(const Data& data, const GpHyperparameters& h) {
    const Eigen::VectorXd& y = data.y;
    const double mean = y.size() > 0 ? y.mean() : 0.0;
    double scale = y.size() > 1 ? std::sqrt((y.array() - mean).square().sum() / static_cast<double>(y.size() - 1)) : 0.0;
    if (!(scale > 0.0)) scale = std::max(1.0, std::abs(mean));  // one value, or all equal: any positive scale
    return GaussianProcess(data, h, mean, scale);
}

GaussianProcess GaussianProcess::fit(const Data& observed) {
    const int d = static_cast<int>(observed.x.cols());
    const int n = 2 + d;
    FitData data{&observed, d};
    std::vector<double> lower(n), upper(n);
    lower[0] = std::log(kMinSignal), upper[0] = std::log(kMaxSignal);
    for (int i = 0; i < d; ++i) lower[1 + i] = std::log(kMinLength), upper[1 + i] = std::log(kMaxLength);
    lower[1 + d] = std::log(kMinNugget), upper[1 + d] = std::log(kMaxNugget);
    // A few starts (lengths short, medium, long; a small nugget): the likelihood has local optima.
    std::vector<double> best_theta;
    double best = std::numeric_limits<double>::infinity();
    for (const double start_length : {0.2, 0.5, 1.5}) {
        std::vector<double> theta(n);
        theta[0] = 0.0;
        for (int i = 0; i < d; ++i) theta[1 + i] = std::log(start_length);
        theta[1 + d] = std::log(1e-3);
        nlopt_opt opt = nlopt_create(NLOPT_LN_BOBYQA, static_cast<unsigned>(n));
        nlopt_set_lower_bounds(opt, lower.data());
        nlopt_set_upper_bounds(opt, upper.data());
        nlopt_set_min_objective(opt, negative_log_likelihood, &data);
        nlopt_set_xtol_rel(opt, 1e-4);
        nlopt_set_maxeval(opt, 400);
        double value = 0.0;
        nlopt_optimize(opt, theta.data(), &value);  // a stop at maxeval still leaves the best point found
        nlopt_destroy(opt);
        if (value < best) best = value, best_theta = theta;
    }
    return with(observed, from_theta(best_theta.data(), d));
}

GpPrediction GaussianProcess::predict(const Eigen::VectorXd& x) const {
    const Eigen::Index n = d_.x.rows();
    if (n == 0) return {y_mean_, h_.signal_variance * y_scale_ * y_scale_};
    Eigen::VectorXd k(n);
    for (Eigen::Index i = 0; i < n; ++i) k(i) = kernel(x, d_.x.row(i).transpose());
    const double mean = k.dot(alpha_);
    const Eigen::VectorXd v = llt_.matrixL().solve(k);
    const double variance = std::max(0.0, h_.signal_variance - v.squaredNorm());
    return {y_mean_ + y_scale_ * mean, variance * y_scale_ * y_scale_};
}

double GaussianProcess::covariance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
    const Eigen::Index n = d_.x.rows();
    double c = kernel(a, b);
    if (n > 0) {
        Eigen::VectorXd ka(n), kb(n);
        for (Eigen::Index i = 0; i < n; ++i) ka(i) = kernel(a, d_.x.row(i).transpose()), kb(i) = kernel(b, d_.x.row(i).transpose());
        c -= llt_.matrixL().solve(ka).dot(llt_.matrixL().solve(kb));
    }
    return c * y_scale_ * y_scale_;
}

GaussianProcess GaussianProcess::with_observation(const Eigen::VectorXd& x, double y, double runs) const {
    Data more;
    more.x.resize(d_.x.rows() + 1, d_.x.cols());
    more.x << d_.x, x.transpose();
    more.y.resize(d_.y.size() + 1);
    more.y << d_.y, y;
    more.runs.resize(d_.runs.size() + 1);
    more.runs << d_.runs, runs;
    more.known_variance.resize(d_.known_variance.size() + 1);
    more.known_variance << d_.known_variance, 0.0;
    more.scatter.resize(d_.scatter.size() + 1);
    more.scatter << d_.scatter, 0.0;
    return GaussianProcess(std::move(more), h_, y_mean_, y_scale_);  // the same standardisation: the same model
}

}  // namespace peensim
