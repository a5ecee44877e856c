#include "fem/dent_profile.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace peensim {

namespace {

std::string upper(std::string s) {
    for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return s;
}

std::string trimmed_line(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

}  // namespace

std::map<int, Vec3> read_inp_nodes(const std::string& inp_path) {
    std::ifstream in(inp_path);
    if (!in) throw std::runtime_error(inp_path + ": cannot open");
    std::map<int, Vec3> nodes;
    bool in_nodes = false;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("**", 0) == 0) continue;
        if (!line.empty() && line[0] == '*') {
            in_nodes =
                upper(line).rfind("*NODE", 0) == 0 && upper(line).rfind("*NODE PRINT", 0) != 0 && upper(line).rfind("*NODE FILE", 0) != 0;
            continue;
        }
        if (!in_nodes || trimmed_line(line).empty()) continue;
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream fields(line);
        int id = 0;
        double x = 0, y = 0, z = 0;
        if (!(fields >> id >> x >> y >> z)) throw std::runtime_error(inp_path + ": bad *NODE line '" + line + "'");
        nodes[id] = Vec3(x, y, z);
    }
    return nodes;
}

// Element id -> its 8 corner node ids, from every *ELEMENT block of an .inp file.
std::map<int, std::array<int, 8>> read_inp_elements(const std::string& inp_path) {
    std::ifstream in(inp_path);
    if (!in) throw std::runtime_error(inp_path + ": cannot open");
    std::map<int, std::array<int, 8>> elements;
    bool reading = false;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("**", 0) == 0) continue;
        if (!line.empty() && line[0] == '*') {
            reading = upper(line).rfind("*ELEMENT", 0) == 0;
            continue;
        }
        if (!reading) continue;
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream f(line);
        int id = 0;
        std::array<int, 8> corners{};
        if (!(f >> id)) continue;
        for (int& c : corners)
            if (!(f >> c)) throw std::runtime_error(inp_path + ": an element with fewer than 8 nodes: " + line);
        elements[id] = corners;
    }
    return elements;
}

std::map<int, Vec3> read_dat_last_table(const std::string& dat_path, const std::string& quantity, const std::string& set) {
    std::ifstream in(dat_path);
    if (!in) throw std::runtime_error(dat_path + ": cannot open");
    const std::string head = " " + quantity + " (vx,vy,vz) for set " + upper(set) + " and time";
    std::map<int, Vec3> table, current;
    bool reading = false;
    for (std::string line; std::getline(in, line);) {
        const std::string t = trimmed_line(line);
        if (upper(line).find(upper(head)) != std::string::npos) {
            reading = true;
            current.clear();
            continue;
        }
        if (!reading) continue;
        if (t.empty()) {
            if (!current.empty()) {
                table = current;
                reading = false;
            }
            continue;
        }
        std::istringstream fields(t);
        int id = 0;
        double x = 0, y = 0, z = 0;
        if (!(fields >> id >> x >> y >> z)) {
            if (!current.empty()) table = current;
            reading = false;
            continue;
        }
        current[id] = Vec3(x, y, z);
    }
    if (reading && !current.empty()) table = current;
    return table;
}

DentProfile dent_profile(const std::vector<Vec3>& points_m, const std::vector<Vec3>& displacements_m) {
    if (points_m.size() != displacements_m.size() || points_m.size() < 2)
        throw std::runtime_error("dent profile: expected at least two nodes with their displacements");
    std::vector<std::size_t> order(points_m.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return points_m[a].x() < points_m[b].x(); });
    std::vector<double> r, w;
    for (std::size_t i : order) {
        r.push_back(points_m[i].x() + displacements_m[i].x());
        w.push_back(displacements_m[i].z());
    }
    DentProfile p;
    p.depth_m = -w.front();
    bool found = false;
    for (std::size_t i = 0; i + 1 < r.size(); ++i)
        if (w[i] < 0.0 && w[i + 1] >= 0.0) {
            p.zero_diameter_m = 2.0 * (r[i] + (r[i + 1] - r[i]) * (-w[i]) / (w[i + 1] - w[i]));
            found = true;
            break;
        }
    if (!found) throw std::runtime_error("dent profile: the surface does not come back to its height within the block");
    const auto crest = std::max_element(w.begin(), w.end());
    p.crest_height_m = *crest;
    p.crest_diameter_m = 2.0 * r[static_cast<std::size_t>(crest - w.begin())];
    return p;
}

}  // namespace peensim
