// A short, printable excerpt of text a user handed peensim, for error messages: a binary file or a
// line of garbage must not print its bytes to the terminal (a tester's random-bytes CSV did). The
// excerpt is quoted, bytes outside printable ASCII are written as \xNN (a quote and a backslash
// escaped too), and text longer than `max_bytes` is cut with "..." and its length said.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

namespace peensim {

inline constexpr std::size_t kExcerptBytes = 40;  // bytes of the text shown at most

inline std::string text_excerpt(std::string_view text, std::size_t max_bytes = kExcerptBytes) {
    std::string s = "'";
    const std::size_t shown = text.size() < max_bytes ? text.size() : max_bytes;
    for (std::size_t i = 0; i < shown; ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c == '\'' || c == '\\') {
            s += '\\';
            s += static_cast<char>(c);
        } else if (c >= 0x20 && c < 0x7f) {
            s += static_cast<char>(c);
        } else {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02X", c);
            s += hex;
        }
    }
    s += '\'';
    if (shown < text.size()) s += "... (" + std::to_string(text.size()) + " bytes)";
    return s;
}

// Whether `text` holds a byte no text file has (a control character other than tab and CR, or
// DEL): the sign of a binary file.
inline bool has_binary_byte(std::string_view text) {
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7f) return true;
    }
    return false;
}

}  // namespace peensim
