// Reads back what CalculiX computed for a deck written by `peensim export-fem`: the node
// coordinates of the deck (.inp, the block's *NODE block) and the last printed displacements of a
// node set (.dat), and from them the dent's radial profile along the deck's x axis from the patch
// centre: depth, the diameter where the permanent vertical displacement comes back to zero, and
// the diameter of the pile-up's crest. Throws std::runtime_error (file: what) for a file that is
// not what ccx writes.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "common/vec.h"

namespace peensim {

// Node id -> coordinates (m) of every *NODE block of an .inp file.
std::map<int, Vec3> read_inp_nodes(const std::string& inp_path);
// Element id -> its 8 corner node ids, from every *ELEMENT block of an .inp file.
std::map<int, std::array<int, 8>> read_inp_elements(const std::string& inp_path);

// Node id -> the values of the last "<quantity> (vx,vy,vz) for set <SET> and time ..." table of a
// ccx .dat file (quantity e.g. "displacements", "velocities"); set names are compared
// case-insensitively. Empty if the file has no such table.
std::map<int, Vec3> read_dat_last_table(const std::string& dat_path, const std::string& quantity, const std::string& set);

struct DentProfile {
    double depth_m = 0.0;           // m, minus the vertical displacement at the centre
    double zero_diameter_m = 0.0;   // m, 2 x the deformed radius where the vertical displacement first comes back to 0
    double crest_diameter_m = 0.0;  // m, 2 x the deformed radius of the highest pile-up
    double crest_height_m = 0.0;    // m, the pile-up's height
};

// From the nodes on the line y = 0, x >= 0 (coordinates and displacements, any order). Throws
// std::runtime_error if the profile never comes back to zero (the dent is wider than the block).
DentProfile dent_profile(const std::vector<Vec3>& points_m, const std::vector<Vec3>& displacements_m);

}  // namespace peensim
