// A CSV file with a header, read as numeric columns by name: what the tests check the analysis'
// tables with. Empty cells and text (a region's name) read as NaN.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace peensim::testing {

inline std::map<std::string, std::vector<double>> read_csv_columns(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    std::vector<std::string> header;
    std::stringstream hs(line);
    for (std::string h; std::getline(hs, h, ',');) header.push_back(h);
    std::map<std::string, std::vector<double>> columns;
    while (std::getline(in, line)) {
        std::stringstream ls(line);
        std::string field;
        for (const std::string& h : header) {
            if (!std::getline(ls, field, ',')) field.clear();
            char* end = nullptr;
            const double value = std::strtod(field.c_str(), &end);
            columns[h].push_back(field.empty() || *end != '\0' ? std::numeric_limits<double>::quiet_NaN() : value);
        }
    }
    return columns;
}

// The sum of a column's numbers (its empty cells left out).
inline double csv_column_sum(const std::filesystem::path& path, const std::string& column) {
    const std::map<std::string, std::vector<double>> columns = read_csv_columns(path);  // outlives the loop
    double sum = 0.0;
    if (const auto c = columns.find(column); c != columns.end())
        for (double v : c->second)
            if (v == v) sum += v;
    return sum;
}

}  // namespace peensim::testing
