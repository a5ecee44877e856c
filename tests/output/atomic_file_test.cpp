#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "output/atomic_file.h"

namespace peensim {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::string pattern = (fs::temp_directory_path() / "peensim-atomic-XXXXXX").string();
        ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
        dir_ = pattern;
    }
    void TearDown() override { fs::remove_all(dir_); }

    static std::string read(const fs::path& path) {
        std::ifstream in(path, std::ios::binary);
        std::ostringstream text;
        text << in.rdbuf();
        return text.str();
    }

    fs::path dir_;
};

TEST_F(AtomicFileTest, WritesContentAndLeavesNoTemporary) {
    const auto path = (dir_ / "summary.json").string();
    write_file_atomically(path, "first");
    EXPECT_EQ(read(path), "first");
    write_file_atomically(path, std::string("second\0with nul", 15));
    EXPECT_EQ(read(path), std::string("second\0with nul", 15));
    EXPECT_FALSE(fs::exists(path + ".tmp"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(AtomicFileTest, FailureNamesThePathAndKeepsOldContent) {
    const auto missing = (dir_ / "no-such-dir" / "out.json").string();
    try {
        write_file_atomically(missing, "x");
        FAIL() << "expected an error";
    } catch (const std::runtime_error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(missing + ".tmp"), std::string::npos) << message;
        EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;
    }

    // Renaming over a directory fails: the temporary is removed and the target untouched.
    const auto blocked = dir_ / "blocked";
    fs::create_directory(blocked);
    fs::create_directory(blocked / "child");
    EXPECT_THROW(write_file_atomically(blocked.string(), "x"), std::runtime_error);
    EXPECT_TRUE(fs::is_directory(blocked / "child"));
    EXPECT_FALSE(fs::exists(blocked.string() + ".tmp"));
}

}  // namespace
}  // namespace peensim
