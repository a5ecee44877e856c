// The message of the InputError a mesh load throws, for the loader's tests: it must name the file
// and the field "mesh"; no error at all is a failure.
#pragma once

#include <gtest/gtest.h>

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

}  // namespace peensim::testing
