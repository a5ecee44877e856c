#include "fem/residual_stress.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "fem/dent_profile.h"

namespace peensim {

std::vector<ResidualStressPoint> read_axis_residual_stress(const std::string& inp_path, const std::string& dat_path) {
    std::ifstream in(dat_path);
    if (!in) throw std::runtime_error(dat_path + ": cannot open");
    // Element id -> summed (sxx, syy, szz) and the count of integration points, of the last table.
    std::map<int, std::array<double, 4>> sums, current;
    bool reading = false;
    for (std::string line; std::getline(in, line);) {
        if (line.find("stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz) for set EAXIS") != std::string::npos) {
            reading = true;
            current.clear();
            continue;
        }
        if (!reading) continue;
        std::istringstream f(line);
        int element = 0, point = 0;
        double sxx = 0, syy = 0, szz = 0;
        if (!(f >> element >> point >> sxx >> syy >> szz)) {
            if (!current.empty()) {
                sums = current;
                reading = false;
            }
            continue;
        }
        auto& s = current[element];
        s[0] += sxx;
        s[1] += syy;
        s[2] += szz;
        s[3] += 1.0;
    }
    if (reading && !current.empty()) sums = current;
    if (sums.empty())
        throw std::runtime_error(dat_path + ": no stress table for set EAXIS (is it a deck with a relaxation step, and did ccx finish?)");
    const auto nodes = read_inp_nodes(inp_path);
    const auto elements = read_inp_elements(inp_path);
    std::vector<ResidualStressPoint> points;
    for (const auto& [id, s] : sums) {
        const auto e = elements.find(id);
        if (e == elements.end()) throw std::runtime_error(inp_path + ": no element " + std::to_string(id) + " (named in " + dat_path + ")");
        double z = 0.0;
        for (int n : e->second) {
            const auto p = nodes.find(n);
            if (p == nodes.end()) throw std::runtime_error(inp_path + ": no node " + std::to_string(n));
            z += p->second.z() / 8.0;
        }
        points.push_back({id, -z, s[0] / s[3], s[1] / s[3], s[2] / s[3]});
    }
    std::sort(points.begin(), points.end(),
              [](const ResidualStressPoint& a, const ResidualStressPoint& b) { return a.depth_m < b.depth_m; });
    return points;
}

}  // namespace peensim
