// Overlap audit of a simulation state at its own time: every pair of active shot and every active
// shot against every component mesh, the mesh placed at its closed-form pose at state.time. Exact
// distances (all pairs, Bullet's closest point in the component frame), so it is a test oracle, not
// fast: O(N^2) pairs per call.
#pragma once

#include <cstdint>
#include <limits>
#include <string>

#include "engine/simulation_state.h"
#include "model/model.h"

namespace peensim::testing {

struct OverlapReport {
    std::uint64_t audits = 0;                                           // states audited
    std::uint64_t pair_overlaps = 0;                                    // shot pairs closer than R_i + R_j - tolerance (summed over audits)
    std::uint64_t mesh_overlaps = 0;                                    // shot closer than R - tolerance to a mesh (summed over audits)
    double worst_pair_gap_m = std::numeric_limits<double>::infinity();  // m, min over pairs of |ci - cj| - (R_i + R_j)
    double worst_mesh_gap_m = std::numeric_limits<double>::infinity();  // m, min of distance - R (within 2R of a mesh)
    std::string first_pair;                                             // numbers of the first pair overlap
    std::string first_mesh;                                             // numbers of the first mesh overlap
    std::string worst_pair;                                             // numbers of the deepest pair overlap
    std::string worst_mesh;                                             // numbers of the deepest mesh overlap
};

class OverlapAudit {
public:
    // tolerance_m (m): a gap above -tolerance is not an overlap.
    OverlapAudit(const Model& model, double tolerance_m);
    void audit(const SimulationState& state);
    const OverlapReport& report() const { return report_; }
    // One line for the test output.
    std::string summary() const;

private:
    const Model& model_;
    double tolerance_m_;
    OverlapReport report_;
};

}  // namespace peensim::testing
