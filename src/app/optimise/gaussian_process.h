// A Gaussian-process regression: the optimiser's model of how a noisy, expensive figure (a time
// to coverage) depends on the process variables, scaled to the unit cube. Matern 5/2 kernel with
// one length scale per variable (ARD), a constant mean, and noise per observation: a variance
// per run fitted with the rest (the nugget), divided by the runs an observation averages, plus
// any variance an observation is known to have.
// The hyperparameters maximise the log marginal likelihood, with the scatter of each
// observation's runs about their mean (which tells the noise from the variables' effect), times a
// Gamma(3, 6) prior on each length scale (mean half the range, as BoTorch's: a few noisy points do
// not make a wiggle); NLopt's BOBYQA from a few starts.
// Rasmussen and Williams, "Gaussian Processes for Machine Learning" (2006), algorithm 2.1 and
// eq. 4.17 (Matern 5/2).
#pragma once

#include <vector>

#include <Eigen/Dense>

namespace peensim {

struct GpHyperparameters {
    double signal_variance = 1.0;  // of the standardised figure
    std::vector<double> length;    // per variable, in unit-cube lengths
    double nugget = 1e-6;          // noise variance of one run (standardised)
};

struct GpPrediction {
    double mean = 0.0;      // of the figure itself (not of a new noisy observation)
    double variance = 0.0;  // of that mean
};

class GaussianProcess {
public:
    // What is observed: one row of x per observation in [0, 1]^d, the figure y, the runs each
    // averages (>= 1: its noise is the nugget / runs), and a variance each is known to have besides
    // (>= 0, in the figure's units squared; 0 for none).
    // scatter: the sum of squares of an observation's runs about their mean (runs - 1 degrees of
    // freedom; 0 for one run).
    struct Data {
        Eigen::MatrixXd x;
        Eigen::VectorXd y, runs, known_variance, scatter;
    };
    // Fits the hyperparameters.
    static GaussianProcess fit(const Data& data);
    // The same data under given hyperparameters (of the standardised figure).
    static GaussianProcess with(const Data& data, const GpHyperparameters& h);

    GpPrediction predict(const Eigen::VectorXd& x) const;
    // The covariance of the figure's means at a and b (a = b: predict(a).variance).
    double covariance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;
    // The model with one more observation of `runs` runs, hyperparameters kept (a batch's "kriging
    // believer": runs = infinity for an observation without noise).
    GaussianProcess with_observation(const Eigen::VectorXd& x, double y, double runs) const;

    // Of the means, and of the runs' scatter about them (the model's noise of one run).
    double log_marginal_likelihood() const { return log_likelihood_; }
    const GpHyperparameters& hyperparameters() const { return h_; }

private:
    GaussianProcess(Data data, const GpHyperparameters& h, double y_mean, double y_scale);
    double kernel(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;

    Data d_;
    GpHyperparameters h_;
    double y_mean_ = 0.0, y_scale_ = 1.0;  // the standardisation: (y - mean) / scale
    Eigen::LLT<Eigen::MatrixXd> llt_;
    Eigen::VectorXd alpha_;
    double log_likelihood_ = 0.0;
};

// The Matern 5/2 correlation at scaled distance r >= 0: (1 + sqrt5 r + 5/3 r^2) exp(-sqrt5 r).
double matern52(double r);

}  // namespace peensim
