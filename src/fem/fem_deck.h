// Everything an Abaqus-format input deck of a patch holds, as plain values (SI): the meshed block
// of the target, the shot mesh and where each shot starts, the materials, the contact penalty and
// the steps. inp_writer.h turns it into text; export_fem_job fills it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/vec.h"
#include "fem/block_mesher.h"
#include "fem/sphere_mesher.h"

namespace peensim {

// The target block's brick. C3D8 integrates fully and locks under the near-incompressible plastic
// flow of a dent (issue 30: C3D8I moved the dent depth +18 % and the rim 2.8x on the same mesh);
// C3D8I (incompatible modes) and C3D8R (reduced integration, CalculiX's hourglass control) do not.
// The convergence study (docs/user-guide.md, "FEM hand-off") chose the default.
enum class FemElement { C3D8, C3D8I, C3D8R };

inline const char* fem_element_name(FemElement e) {
    switch (e) {
        case FemElement::C3D8: return "C3D8";
        case FemElement::C3D8R: return "C3D8R";
        case FemElement::C3D8I: break;
    }
    return "C3D8I";
}

struct FemMaterial {
    std::string name;                       // deck name (upper case, no spaces)
    double youngs_modulus_pa = 0.0;         // Pa, E
    double poisson_ratio = 0.0;             // -, nu
    double density_kg_per_m3 = 0.0;         // kg/m3
    std::optional<double> yield_stress_pa;  // Pa; empty = elastic only
    double hardening_modulus_pa = 0.0;      // Pa, slope of the yield stress against plastic strain (0 = perfectly plastic)
};

// One shot: a copy of the shot mesh moved to `start_centre_m` with `velocity_m_per_s` at t = 0.
struct FemShot {
    Vec3 start_centre_m = Vec3::Zero();    // m, patch frame, at t = 0
    Vec3 velocity_m_per_s = Vec3::Zero();  // m/s, patch frame
    int step = 0;                          // 0-based step it lands in
    int impact = 0;                        // index into the export's impact list
};

struct FemStep {
    double duration_s = 0.0;           // s
    double initial_increment_s = 0.0;  // s
    double max_increment_s = 0.0;      // s
    std::vector<int> shots;            // indices into FemDeck::shots landing in this step
};

struct FemDeck {
    std::vector<std::string> header;               // comment lines (without the leading "**")
    std::string heading;                           // *HEADING text (one line)
    BlockMesh block;                               // patch frame: surface z = 0, material below
    SphereMesh shot_mesh;                          // centred at the origin
    bool quarter = false;                          // symmetry planes x = 0 and y = 0
    FemElement block_element = FemElement::C3D8I;  // the block's brick (the shot's stay C3D8: elastic, no plastic flow to lock)
    FemMaterial target, shot;
    std::vector<FemShot> shots;
    std::vector<FemStep> steps;
    double contact_stiffness_pa_per_m = 0.0;  // Pa/m, penalty: contact pressure per overclosure
    double alpha = -0.3;                      // -, Hilber-Hughes-Taylor alpha of the implicit *DYNAMIC (numerical damping)
    // The impacts' steps: *DYNAMIC, EXPLICIT (central differences at ccx's stable increment, no
    // equation solve per increment) or the implicit *DYNAMIC (Hilber-Hughes-Taylor; ccx's contact
    // rules cut its increments to ~1e-9 s around each contact, each a Newton solve).
    bool explicit_dynamics = true;
};

// Node and element numbers the writer gives (1-based, as in the deck): the block first, then the
// shots one after the other.
inline int block_node_id(int node) { return node + 1; }
inline int block_element_id(int element) { return element + 1; }
inline int shot_node_id(const FemDeck& d, int shot, int node) {
    return static_cast<int>(d.block.mesh.nodes.size()) + shot * static_cast<int>(d.shot_mesh.mesh.nodes.size()) + node + 1;
}
inline int shot_element_id(const FemDeck& d, int shot, int element) {
    return static_cast<int>(d.block.mesh.elements.size()) + shot * static_cast<int>(d.shot_mesh.mesh.elements.size()) + element + 1;
}

}  // namespace peensim
