// The words of a line of a text mesh file (ASCII STL, OBJ) with their columns, and whether a
// word is a number: what the line-by-line checks (ascii_stl_check.h, obj_check.h) share.
#pragma once

#include <charconv>
#include <cmath>
#include <string_view>
#include <vector>

namespace peensim {

struct TextWord {
    std::string_view text;
    int column = 0;  // 1-based
};

inline bool is_blank_char(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// The words of `line` into `words` (cleared first; no allocation past the vector's growth).
inline void split_words(std::string_view line, std::vector<TextWord>& words) {
    words.clear();
    for (std::size_t i = 0; i < line.size();) {
        while (i < line.size() && is_blank_char(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !is_blank_char(line[i])) ++i;
        if (i > start) words.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
    }
}

// Whether the whole word is a decimal number ("+" allowed in front, as writers emit it; "nan" and
// "inf" are numbers here), its value in `value`: not "2x", which a reader taking the digits at its
// front reads as 2.
inline bool read_number(std::string_view word, double& value) {
    if (!word.empty() && word.front() == '+') word.remove_prefix(1);
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    return error == std::errc() && end == word.data() + word.size();
}

inline bool is_number(std::string_view word) {
    double value = 0.0;
    return read_number(word, value);
}

inline bool is_finite_number(std::string_view word) {
    double value = 0.0;
    return read_number(word, value) && std::isfinite(value);
}

}  // namespace peensim
