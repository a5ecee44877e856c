// Reads back the residual stresses CalculiX printed for a deck of `peensim export-fem`: the last
// "stresses (elem, integ.pnt., sxx, ...) for set EAXIS" table of the .dat (written by the deck's
// relaxation step, so after equilibrium without the shot), each element's integration points
// averaged and placed at the depth of its centroid (from the .inp's nodes and elements). Throws
// std::runtime_error (file: what) for a file that is not what ccx writes or lacks the table.
#pragma once

#include <string>
#include <vector>

namespace peensim {

struct ResidualStressPoint {
    int element = 0;       // the deck's element id
    double depth_m = 0.0;  // m, below the undeformed surface (z = 0), of the element's centroid
    double sxx_pa = 0.0;   // Pa, in-plane (the deck's x)
    double syy_pa = 0.0;   // Pa, in-plane (y)
    double szz_pa = 0.0;   // Pa, along the normal
};

// Shallowest first.
std::vector<ResidualStressPoint> read_axis_residual_stress(const std::string& inp_path, const std::string& dat_path);

}  // namespace peensim
