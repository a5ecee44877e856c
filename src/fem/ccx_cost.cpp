#include "fem/ccx_cost.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace peensim {

namespace {

// Fitted (tests/bench/fem_cost_fit.py) to the ccx runs of the table in docs/user-guide.md, per block element and
// dynamics: wall = seconds x planned increments x (nodes / 1e4)^exponent, peak memory = bytes x
// (nodes / 1e4)^exponent. Explicit: about linear in the nodes (no equation solve per increment);
// implicit: a Newton solve per increment and ccx's contact cutbacks, steeper. Laws not measured
// (explicit C3D8 and C3D8R; implicit C3D8R, which did not finish) take C3D8I's of their dynamics.
struct CostLaw {
    double seconds_per_increment;  // s, at kReferenceNodes
    double time_exponent;          // -
    double bytes;                  // B, at kReferenceNodes
    double memory_exponent;        // -
};
constexpr double kReferenceNodes = 1e4;  // -
constexpr CostLaw kExplicitC3D8I{1.573, 1.050, 415.4e6, 1.061};
constexpr CostLaw kImplicitC3D8I{337.3, 2.486, 647.6e6, 1.196};
constexpr CostLaw kImplicitC3D8{94.29, 2.486, 437.5e6, 1.196};

CostLaw cost_law(const FemDeck& deck) {
    if (deck.explicit_dynamics) return kExplicitC3D8I;
    return deck.block_element == FemElement::C3D8 ? kImplicitC3D8 : kImplicitC3D8I;
}

// The shortest element edge of a mesh (m).
double shortest_edge(const HexMesh& mesh) {
    static constexpr int kEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    double shortest = std::numeric_limits<double>::infinity();
    for (const HexElement& e : mesh.elements)
        for (const auto& k : kEdges)
            shortest = std::min(shortest, (mesh.nodes[static_cast<std::size_t>(e[static_cast<std::size_t>(k[0])])] -
                                           mesh.nodes[static_cast<std::size_t>(e[static_cast<std::size_t>(k[1])])])
                                              .norm());
    return shortest;
}

// Dilatational wave speed (m/s) of a material: sqrt(E (1 - nu) / (rho (1 + nu) (1 - 2 nu))).
double wave_speed(const FemMaterial& m) {
    const double nu = m.poisson_ratio;
    return std::sqrt(m.youngs_modulus_pa * (1.0 - nu) / (m.density_kg_per_m3 * (1.0 + nu) * (1.0 - 2.0 * nu)));
}

}  // namespace

double stable_increment(const FemDeck& deck) {
    const double block = shortest_edge(deck.block.mesh) / wave_speed(deck.target);
    if (deck.shots.empty()) return block;
    return std::min(block, shortest_edge(deck.shot_mesh.mesh) / wave_speed(deck.shot));
}

namespace {

double planned_increments(const FemDeck& deck) {
    double n = 0.0;
    const double explicit_increment = deck.explicit_dynamics ? stable_increment(deck) : 0.0;
    for (const FemStep& s : deck.steps) n += std::ceil(s.duration_s / (deck.explicit_dynamics ? explicit_increment : s.max_increment_s));
    return n;
}

}  // namespace

CcxCostEstimate estimate_ccx_cost(const FemDeck& deck) {
    CcxCostEstimate c;
    c.nodes = static_cast<double>(deck.block.mesh.nodes.size() + deck.shots.size() * deck.shot_mesh.mesh.nodes.size());
    c.planned_increments = planned_increments(deck);
    const double scale = c.nodes / kReferenceNodes;
    const CostLaw law = cost_law(deck);
    c.seconds = law.seconds_per_increment * c.planned_increments * std::pow(scale, law.time_exponent);
    c.bytes = law.bytes * std::pow(scale, law.memory_exponent);
    return c;
}

}  // namespace peensim
