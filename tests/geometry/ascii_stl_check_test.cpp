// check_ascii_stl: an ASCII STL that breaks its grammar is refused at its line and column with
// what was expected; the forms writers really emit (any case, "+" signs, CRLF, blank lines, a
// facet without its normal or with a "nan" one, several solids) pass.
#include "geometry/ascii_stl_check.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "common/input_error.h"
#include "support/mesh_error.h"

namespace peensim {
namespace {

const std::string kFacet =
    "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n    endloop\n  endfacet\n";

void expect_stl_refused_at(const std::string& text, int line, int column, const std::string& phrase) {
    testing::expect_text_mesh_refused_at([](const std::string& file, std::istream& in) { check_ascii_stl(file, in); }, text, line, column,
                                         phrase);
}

TEST(AsciiStlCheck, TheFormsWritersEmitPass) {
    const std::string text =
        "SOLID Part 1 (from a CAD tool)\r\n\r\n"
        "FACET NORMAL +0.0 -0 1E+0\r\nOUTER LOOP\r\nVERTEX +1.5e-3 0 0\r\nVERTEX 1 0 0\r\nVERTEX 0 1 0\r\nENDLOOP\r\nENDFACET\r\n"
        "endsolid\r\n"
        // A degenerate facet's normal as some writers give it (the reader ignores normals).
        "solid degenerate\nfacet normal -nan nan -nan\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 2 0 0\nendloop\nendfacet\n"
        "endsolid degenerate\n"
        "solid second\n  facet\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n"
        "    endloop\n  endfacet\n" +
        kFacet + "endsolid second\n";
    std::istringstream in(text);
    EXPECT_NO_THROW(check_ascii_stl("part.stl", in));
}

TEST(AsciiStlCheck, ANumberWithAWordAfterItIsRefusedNotReadAsItsDigits) {
    // The reader took "2x" for 2: a part silently of other coordinates.
    expect_stl_refused_at("solid s\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 2x\n", 5, 18,
                          "expected a finite number in 'vertex', got '2x'");
    expect_stl_refused_at("solid s\n  facet normal 0 0 1n\n", 2, 20, "expected a number in 'facet normal', got '1n'");
    expect_stl_refused_at("solid s\n  facet normal 0 0 1\n    outer loop\n      vertex 1e400 0 0\n", 4, 14,
                          "expected a finite number in 'vertex', got '1e400'");
}

TEST(AsciiStlCheck, AVertexOfOtherThanThreeNumbersIsRefused) {
    expect_stl_refused_at("solid s\n  facet normal 0 0 1\n    outer loop\n      vertex 1 0\n", 4, 7,
                          "expected 'vertex' followed by three numbers, got '      vertex 1 0'");
    expect_stl_refused_at("solid s\n  facet normal 0 0 1\n    outer loop\n      vertex 1,0,0\n", 4, 7, "three numbers");
    expect_stl_refused_at("solid s\n  facet normal 0 0 1\n    outer loop\n      vertex 1 0 0 7\n", 4, 7, "three numbers");
}

TEST(AsciiStlCheck, AFacetOfOtherThanThreeVerticesIsRefused) {
    expect_stl_refused_at("solid s\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n    endloop\n", 6, 5,
                          "a facet of 2 vertices");
    expect_stl_refused_at(
        "solid s\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n"
        "      vertex 1 1 0\n",
        7, 7, "a facet of more than three vertices");
}

TEST(AsciiStlCheck, AKeywordOutOfPlaceIsRefusedWithWhatWasExpected) {
    expect_stl_refused_at("solid s\n  facet normal 0 0 1\n    vertex 0 0 0\n", 3, 5, "expected 'outer loop'");
    expect_stl_refused_at("solid s\n" + kFacet + "  endloop\n", 9, 3, "expected 'facet normal X Y Z' or 'endsolid'");
    expect_stl_refused_at(
        "solid s\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n"
        "    endloop\n  endloop\n",
        8, 3, "expected 'endfacet'");
    expect_stl_refused_at("  facet normal 0 0 1\n", 1, 3, "expected 'solid'");
    expect_stl_refused_at("solid s\n  facet norml 0 0 1\n", 2, 9, "expected 'facet normal X Y Z'");
}

TEST(AsciiStlCheck, AFileThatEndsInsideASolidIsTruncated) {
    expect_stl_refused_at("solid s\n" + kFacet, 8, 0, "the file ends inside a solid (no 'endsolid' after line 8)");
    expect_stl_refused_at("solid s\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n", 4, 0, "a truncated file");
}

}  // namespace
}  // namespace peensim
