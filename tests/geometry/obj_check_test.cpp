// check_obj: an OBJ file whose numbers or face corners are broken is refused at its line and
// column with what was expected; what writers really emit (w and colours on v, v/vt/vn corners,
// negative corners, a face before its vertices, continued lines, other keywords) passes.
#include "geometry/obj_check.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "common/input_error.h"
#include "support/mesh_error.h"

namespace peensim {
namespace {

const std::string kTetrahedron = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";

void expect_obj_refused_at(const std::string& text, int line, int column, const std::string& phrase) {
    testing::expect_text_mesh_refused_at([](const std::string& file, std::istream& in) { check_obj(file, in); }, text, line, column,
                                         phrase);
}

TEST(ObjCheck, TheFormsWritersEmitPass) {
    const std::string text =
        "# exported\r\nmtllib part.mtl\r\no part\r\nf 1 2 3\r\n" + kTetrahedron +
        "v 1 1 1 1.0\nv 1 1 0 0.5 0.5 0.5\nvt 0.5\nvt 0.5 0.5\nvn 0 0 +1\nvn nan -nan nan\ng alpha beta\nusemtl steel\ns 1\n"
        "f 1/1 2/2 3/2\nf 1//1 2//1 4//1\nf 1/1/1 3/2/1 4/1/1\nf -6 -5 \\\n -3\nl 1 2 3\np 5\n";
    std::istringstream in(text);
    EXPECT_NO_THROW(check_obj("part.obj", in));
}

TEST(ObjCheck, ANumberWithAWordAfterItIsRefusedNotReadAsItsDigits) {
    // The reader took "2x" for 2, and "garbage" for a missing coordinate (then "vertex index out
    // of range", with no line).
    expect_obj_refused_at("v 0 0 0\nv 10 0 0\nv 0 10 2x\n", 3, 8, "expected a finite number in 'v', got '2x'");
    expect_obj_refused_at("v 0 0 0\nv 10 0 garbage\n", 2, 8, "expected a finite number in 'v', got 'garbage'");
    expect_obj_refused_at("vn 0 0 1n\n", 1, 8, "expected a number in 'vn', got '1n'");
    expect_obj_refused_at("v 0 0 inf\n", 1, 7, "expected a finite number in 'v', got 'inf'");
}

TEST(ObjCheck, AVertexOfTooFewOrTooManyNumbersIsRefused) {
    expect_obj_refused_at("v 0 0\n", 1, 1, "expected 'v' with 3 to 7 numbers");
    expect_obj_refused_at("v 0 0 0 1 1 1 1 1\n", 1, 1, "expected 'v' with 3 to 7 numbers");
    expect_obj_refused_at("vn 0 1\n", 1, 1, "expected 'vn' with 3 numbers");
}

TEST(ObjCheck, ABrokenCornerIsRefusedAtItsColumn) {
    expect_obj_refused_at(kTetrahedron + "f 1 2 x\n", 5, 7, "expected a corner 'v', 'v/vt', 'v//vn' or 'v/vt/vn'");
    expect_obj_refused_at(kTetrahedron + "f 1 0 3\n", 5, 5, "got '0'");
    expect_obj_refused_at(kTetrahedron + "f 1 2.5 3\n", 5, 5, "got '2.5'");
    expect_obj_refused_at(kTetrahedron + "f 1 2/1/1/1 3\n", 5, 5, "got '2/1/1/1'");
    expect_obj_refused_at(kTetrahedron + "f 1 2/ 3\n", 5, 5, "got '2/'");
    expect_obj_refused_at(kTetrahedron + "f 1 2\n", 5, 1, "expected 'f' with 3 corners at least");
}

TEST(ObjCheck, ACornerPastTheVerticesIsRefusedAtItsLine) {
    expect_obj_refused_at(kTetrahedron + "f 1 2 3\nf 1 2 9\nf 1 3 4\n", 6, 7, "a corner names vertex 9, but the file has 4");
    expect_obj_refused_at(kTetrahedron + "f -1 -2 -5\n", 5, 9, "corner '-5' counts back 5 vertices, but only 4 come before it");
}

}  // namespace
}  // namespace peensim
