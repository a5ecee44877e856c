#include "geometry/ascii_stl_check.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string_view>
#include <vector>

#include "common/input_error.h"
#include "geometry/text_words.h"

namespace peensim {

namespace {

// Where the grammar is: what the next keyword line may be.
enum class Expect { solid, facet_or_endsolid, outer_loop, vertex, endloop, endfacet };

bool same_word(std::string_view word, std::string_view keyword) {
    return word.size() == keyword.size() && std::equal(word.begin(), word.end(), keyword.begin(),
                                                       [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
}

}  // namespace

void check_ascii_stl(const std::string& path, std::istream& in) {
    int line_number = 0;
    const auto refuse = [&](int column, const std::string& problem) {
        throw InputError(SourceLocation{path, line_number, column}, "mesh", "ASCII STL: " + problem);
    };
    Expect expect = Expect::solid;
    int vertices = 0;  // of the facet open
    std::string line;
    std::vector<TextWord> words;
    // A facet's normal may be any number: the reader ignores it (the winding decides), and writers
    // give a degenerate facet "nan" ones. A vertex's must be finite.
    const auto numbers_after = [&](std::size_t first, const char* what, bool finite) {
        if (words.size() != first + 3)
            refuse(words.front().column, std::string("expected '") + what + "' followed by three numbers, got '" + line + "'");
        for (std::size_t k = first; k < words.size(); ++k)
            if (!(finite ? is_finite_number(words[k].text) : is_number(words[k].text)))
                refuse(words[k].column, std::string("expected a ") + (finite ? "finite " : "") + "number in '" + what + "', got '" +
                                            std::string(words[k].text) + "'");
    };
    while (std::getline(in, line)) {
        ++line_number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        split_words(line, words);
        if (words.empty()) continue;
        const std::string_view key = words.front().text;
        const int column = words.front().column;
        switch (expect) {
            case Expect::solid:
                if (!same_word(key, "solid")) refuse(column, "expected 'solid' (a solid's first line), got '" + line + "'");
                expect = Expect::facet_or_endsolid;
                break;
            case Expect::facet_or_endsolid:
                if (same_word(key, "endsolid")) {
                    expect = Expect::solid;
                } else if (same_word(key, "facet")) {
                    if (words.size() > 1) {
                        if (!same_word(words[1].text, "normal"))
                            refuse(words[1].column, "expected 'facet normal X Y Z', got '" + line + "'");
                        numbers_after(2, "facet normal", false);
                    }
                    expect = Expect::outer_loop;
                } else {
                    refuse(column, "expected 'facet normal X Y Z' or 'endsolid', got '" + line + "'");
                }
                break;
            case Expect::outer_loop:
                if (!same_word(key, "outer") || words.size() != 2 || !same_word(words[1].text, "loop"))
                    refuse(column, "expected 'outer loop', got '" + line + "'");
                expect = Expect::vertex;
                vertices = 0;
                break;
            case Expect::vertex:
                if (same_word(key, "endloop")) {
                    refuse(column,
                           "a facet of " + std::to_string(vertices) + " vertices: expected three 'vertex X Y Z' lines before 'endloop'");
                }
                if (!same_word(key, "vertex")) refuse(column, "expected 'vertex X Y Z', got '" + line + "'");
                numbers_after(1, "vertex", true);
                if (++vertices == 3) expect = Expect::endloop;
                break;
            case Expect::endloop:
                if (!same_word(key, "endloop") || words.size() != 1)
                    refuse(column, same_word(key, "vertex") ? "a facet of more than three vertices: expected 'endloop'"
                                                            : "expected 'endloop', got '" + line + "'");
                expect = Expect::endfacet;
                break;
            case Expect::endfacet:
                if (!same_word(key, "endfacet") || words.size() != 1) refuse(column, "expected 'endfacet', got '" + line + "'");
                expect = Expect::facet_or_endsolid;
                break;
        }
    }
    if (in.bad()) refuse(0, "the file could not be read to its end");
    if (expect != Expect::solid)
        refuse(0, "the file ends inside a solid (no 'endsolid' after line " + std::to_string(line_number) + "): a truncated file");
}

}  // namespace peensim
