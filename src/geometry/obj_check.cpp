#include "geometry/obj_check.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "common/input_error.h"
#include "geometry/text_words.h"

namespace peensim {

namespace {

// A whole integer word, or false.
bool whole(std::string_view word, std::int64_t& value) {
    if (word.empty()) return false;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    return error == std::errc() && end == word.data() + word.size();
}

// A vertex reference past the vertices read so far: checked at the file's end (readers take a
// face before the vertices it names).
struct LaterVertex {
    std::int64_t index = 0;  // 1-based
    int line = 0;
    int column = 0;
};

}  // namespace

void check_obj(const std::string& path, std::istream& in) {
    int line_number = 0, statement_line = 0;
    const auto refuse_at = [&](int line, int column, const std::string& problem) {
        throw InputError(SourceLocation{path, line, column}, "mesh", "OBJ: " + problem);
    };
    const auto refuse = [&](int column, const std::string& problem) { refuse_at(statement_line, column, problem); };
    std::int64_t vertices = 0;
    LaterVertex furthest;  // the furthest reference past the vertices read at its line
    std::string line, statement;
    std::vector<TextWord> words;
    while (std::getline(in, line)) {
        ++line_number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (statement.empty()) statement_line = line_number;
        if (!line.empty() && line.back() == '\\') {  // goes on on the next line
            line.back() = ' ';
            statement += line;
            continue;
        }
        statement += line;
        const std::string text = std::move(statement);
        statement.clear();
        split_words(text, words);
        if (words.empty() || words.front().text.front() == '#') continue;
        const std::string_view key = words.front().text;
        // A vertex's numbers must be finite; a normal's or a texture coordinate's may be any number
        // ("nan" from a writer's degenerate face): the reader uses neither.
        const auto numbers = [&](std::size_t least, std::size_t most, const char* what, bool finite) {
            const std::size_t n = words.size() - 1;
            if (n < least || n > most)
                refuse(words.front().column, std::string("expected '") + std::string(key) + "' with " + what + ", got '" + text + "'");
            for (std::size_t k = 1; k < words.size(); ++k)
                if (!(finite ? is_finite_number(words[k].text) : is_number(words[k].text)))
                    refuse(words[k].column, std::string("expected a ") + (finite ? "finite " : "") + "number in '" + std::string(key) +
                                                "', got '" + std::string(words[k].text) + "'");
        };
        if (key == "v") {
            numbers(3, 7, "3 to 7 numbers (x y z [w] or x y z r g b)", true);
            ++vertices;
        } else if (key == "vn") {
            numbers(3, 3, "3 numbers", false);
        } else if (key == "vt") {
            numbers(1, 3, "1 to 3 numbers", false);
        } else if (key == "f" || key == "l" || key == "p") {
            const std::size_t least = key == "f" ? 3 : key == "l" ? 2 : 1;
            if (words.size() - 1 < least)
                refuse(words.front().column,
                       "expected '" + std::string(key) + "' with " + std::to_string(least) + " corners at least, got '" + text + "'");
            for (std::size_t k = 1; k < words.size(); ++k) {
                const std::string_view corner = words[k].text;
                const std::string_view first = corner.substr(0, corner.find('/'));
                std::int64_t index = 0;
                bool ok = whole(first, index) && index != 0;
                // The texture and normal numbers after it, each whole (or empty: v//vn).
                for (std::size_t slash = corner.find('/'), parts = 1; ok && slash != std::string_view::npos; ++parts) {
                    const std::size_t next = corner.find('/', slash + 1);
                    const std::string_view part =
                        corner.substr(slash + 1, next == std::string_view::npos ? std::string_view::npos : next - slash - 1);
                    std::int64_t other = 0;
                    ok = parts < 3 && ((part.empty() && next != std::string_view::npos) || (whole(part, other) && other != 0));
                    slash = next;
                }
                if (!ok)
                    refuse(words[k].column, "expected a corner 'v', 'v/vt', 'v//vn' or 'v/vt/vn' of whole non-zero numbers in '" +
                                                std::string(key) + "', got '" + std::string(corner) + "'");
                if (index < 0 && -index > vertices)
                    refuse(words[k].column, "corner '" + std::string(corner) + "' counts back " + std::to_string(-index) +
                                                " vertices, but only " + std::to_string(vertices) + " come before it");
                if (index > vertices && index > furthest.index) furthest = {index, statement_line, words[k].column};
            }
        }
    }
    if (in.bad()) refuse_at(line_number, 0, "the file could not be read to its end");
    if (furthest.index > vertices)
        refuse_at(furthest.line, furthest.column,
                  "a corner names vertex " + std::to_string(furthest.index) + ", but the file has " + std::to_string(vertices));
}

}  // namespace peensim
