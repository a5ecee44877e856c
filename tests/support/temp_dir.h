// A fresh directory under /tmp for one test, removed with everything in it when the test ends.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

namespace peensim::testing {

struct TempDir {
    std::filesystem::path path;
    TempDir() {
        std::string name = "/tmp/peensim-test-XXXXXX";
        path = mkdtemp(name.data());
    }
    ~TempDir() { std::filesystem::remove_all(path); }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
};

}  // namespace peensim::testing
