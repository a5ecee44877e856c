// One column of a CSV file the analysis wrote (a header row of names, then rows of plain cells: no
// quoting), by its name: as text, or as numbers (NaN for an empty cell). The readers of the
// analysis' tables (render-impacts, the sweep's 3D views) share it.
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace peensim {

// Throws std::runtime_error naming the file for a file that cannot be read or a missing column.
inline std::vector<std::string> read_csv_texts(const std::filesystem::path& csv, const std::string& column) {
    std::ifstream in(csv);
    if (!in) throw std::runtime_error(csv.string() + ": not found");
    std::string line;
    std::getline(in, line);
    std::vector<std::string> header;
    std::stringstream hs(line);
    for (std::string h; std::getline(hs, h, ',');) header.push_back(h);
    const auto it = std::find(header.begin(), header.end(), column);
    if (it == header.end()) throw std::runtime_error(csv.string() + ": no column '" + column + "'");
    const auto col = static_cast<std::size_t>(it - header.begin());
    std::vector<std::string> values;
    while (std::getline(in, line)) {
        std::stringstream ls(line);
        std::string field;
        for (std::size_t k = 0; k <= col; ++k)
            if (!std::getline(ls, field, ',')) field.clear();
        values.push_back(field);
    }
    return values;
}

inline std::vector<double> read_csv_numbers(const std::filesystem::path& csv, const std::string& column) {
    std::vector<double> values;
    for (const std::string& cell : read_csv_texts(csv, column)) {
        try {
            values.push_back(cell.empty() ? std::numeric_limits<double>::quiet_NaN() : std::stod(cell));
        } catch (const std::exception&) {
            throw std::runtime_error(csv.string() + ": '" + cell + "' in column '" + column + "' is not a number");
        }
    }
    return values;
}

}  // namespace peensim
