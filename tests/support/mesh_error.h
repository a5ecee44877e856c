// The message of the InputError a mesh load throws, for the loader's tests: it must name the file
// and the field "mesh"; no error at all is a failure. And where a text mesh file's check refuses it.
#pragma once

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "common/input_error.h"

namespace peensim::testing {

template <class Load>
std::string mesh_error_of(const std::string& file, Load&& load) {
    try {
        load();
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "mesh");
        EXPECT_EQ(e.where().file, file);
        return e.what();
    }
    ADD_FAILURE() << "no InputError for " << file;
    return "";
}

// For the line-by-line checks of text mesh files (check(file, stream), e.g. check_obj): `text`
// is refused at `line` and `column` of "part" with `phrase` in the message.
template <class Check>
void expect_text_mesh_refused_at(Check&& check, const std::string& text, int line, int column, const std::string& phrase) {
    std::istringstream in(text);
    try {
        check("part", in);
        ADD_FAILURE() << "accepted:\n" << text;
    } catch (const InputError& e) {
        EXPECT_EQ(e.where().file, "part");
        EXPECT_EQ(e.where().line, line) << e.what();
        EXPECT_EQ(e.where().column, column) << e.what();
        EXPECT_EQ(e.field(), "mesh");
        EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos) << e.what();
    }
}

}  // namespace peensim::testing
