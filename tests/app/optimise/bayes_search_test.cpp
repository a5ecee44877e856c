// The optimiser's search (app/optimise/bayes_search.h): expected improvement's exact values, the
// Latin hypercube's strata, and searches of known noisy functions: the minimum found within a
// budget in most of 10 repeats and sooner than random settings, a constraint's boundary found,
// a batch of distinct proposals.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <set>

#include "app/optimise/bayes_search.h"

namespace peensim::testing {
namespace bayes_search_cases {
namespace {

TEST(BayesSearch, ExpectedImprovementExactValues) {
    EXPECT_DOUBLE_EQ(expected_improvement({1.0, 0.0}, 2.0), 1.0);  // certain: the improvement itself
    EXPECT_DOUBLE_EQ(expected_improvement({3.0, 0.0}, 2.0), 0.0);
    EXPECT_NEAR(expected_improvement({0.0, 1.0}, 0.0), 1.0 / std::sqrt(2.0 * std::numbers::pi), 1e-15);  // s phi(0)
    // m = 1, s = 2, best = 0: z = -0.5; (0 - 1) Phi(-0.5) + 2 phi(-0.5).
    const double phi = std::exp(-0.125) / std::sqrt(2.0 * std::numbers::pi), Phi = 0.5 * std::erfc(0.5 / std::numbers::sqrt2);
    EXPECT_NEAR(expected_improvement({1.0, 4.0}, 0.0), -Phi + 2.0 * phi, 1e-15);
}

TEST(BayesSearch, LatinHypercubeHasOnePointPerStratumAndIsReproducible) {
    const auto pts = latin_hypercube(8, 3, 42);
    ASSERT_EQ(pts.size(), 8u);
    for (int i = 0; i < 3; ++i) {
        std::set<int> strata;
        for (const auto& p : pts) strata.insert(static_cast<int>(p(i) * 8.0));
        EXPECT_EQ(strata.size(), 8u) << "variable " << i;
    }
    const auto again = latin_hypercube(8, 3, 42);
    for (std::size_t k = 0; k < pts.size(); ++k) EXPECT_EQ(pts[k], again[k]);
}

// A search loop as the job runs it: a design of 6, then rounds of 2, one run each.
struct Search {
    std::vector<SearchPoint> points;
    Eigen::VectorXd best;
};

template <class F>
Search search(F&& f, int d, int budget, std::uint64_t seed, std::size_t constraints = 0) {
    Search s;
    for (const Eigen::VectorXd& u : latin_hypercube(6, d, seed)) s.points.push_back(f(u));
    for (int round = 1; static_cast<int>(s.points.size()) < budget; ++round) {
        const SearchModel model(s.points, constraints);
        for (const Eigen::VectorXd& u : model.propose(s.points, 2, seed * 100 + static_cast<std::uint64_t>(round)))
            s.points.push_back(f(u));
    }
    const SearchModel model(s.points, constraints);
    s.best = s.points[model.incumbent(s.points)].u;
    return s;
}

// f = (u0 - 0.3)^2 + (u1 - 0.7)^2, noise sd 0.01: 24 runs find the minimum within 0.1 in at least
// 9 of 10 repeats, and land closer on average than 24 random settings (their best measured one).
TEST(BayesSearch, FindsTheMinimumOfANoisyBowlSoonerThanRandomSettings) {
    double search_distance = 0.0, random_distance = 0.0;
    int close = 0;
    const Eigen::Vector2d optimum(0.3, 0.7);
    for (std::uint64_t repeat = 1; repeat <= 10; ++repeat) {
        std::mt19937_64 rng(repeat);
        std::normal_distribution<double> noise(0.0, 0.01);
        const auto bowl = [&](const Eigen::VectorXd& u) {
            SearchPoint p;
            p.u = u;
            p.y = (u - optimum).squaredNorm() + noise(rng);
            return p;
        };
        const Search s = search(bowl, 2, 24, repeat);
        search_distance += (s.best - optimum).norm();
        close += (s.best - optimum).norm() < 0.1;
        std::uniform_real_distribution<double> uniform(0.0, 1.0);
        SearchPoint best_random;
        best_random.y = INFINITY;
        for (int k = 0; k < 24; ++k) {
            const SearchPoint p = bowl(Eigen::Vector2d(uniform(rng), uniform(rng)));
            if (p.y < best_random.y) best_random = p;
        }
        random_distance += (best_random.u - optimum).norm();
    }
    EXPECT_GE(close, 9);
    EXPECT_LT(search_distance, 0.5 * random_distance) << search_distance / 10 << " vs random " << random_distance / 10;
}

// Minimise u0 + u1 / 10 subject to u0 >= 0.6 (g = (0.6 - u0) / 0.6 <= 0): the search ends at the boundary.
TEST(BayesSearch, AConstraintsBoundaryIsFound) {
    const auto f = [](const Eigen::VectorXd& u) {
        SearchPoint p;
        p.u = u;
        p.y = u(0) + 0.1 * u(1);
        p.g = {(0.6 - u(0)) / 0.6};
        return p;
    };
    const Search s = search(f, 2, 26, 3, 1);
    EXPECT_GE(s.best(0), 0.6 - 0.01);
    EXPECT_LT(s.best(0), 0.7);
    EXPECT_LT(s.best(1), 0.3);
}

// A batch: distinct settings (each next one chosen as if the earlier had measured the model's mean).
TEST(BayesSearch, ABatchIsOfDistinctSettings) {
    std::vector<SearchPoint> points;
    for (const Eigen::VectorXd& u : latin_hypercube(5, 2, 9)) {
        SearchPoint p;
        p.u = u;
        p.y = std::sin(5.0 * u(0)) + u(1);
        points.push_back(p);
    }
    const SearchModel model(points, 0);
    const auto batch = model.propose(points, 4, 1);
    ASSERT_EQ(batch.size(), 4u);
    for (std::size_t a = 0; a < batch.size(); ++a)
        for (std::size_t b = a + 1; b < batch.size(); ++b) EXPECT_GT((batch[a] - batch[b]).norm(), 1e-3) << a << " " << b;
    const auto again = model.propose(points, 4, 1);
    for (std::size_t k = 0; k < batch.size(); ++k) EXPECT_EQ(batch[k], again[k]);
}

}  // namespace
}  // namespace bayes_search_cases
}  // namespace peensim::testing
