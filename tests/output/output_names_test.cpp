// What becomes a file: a name joined to an output directory stays inside it (export-fem --name),
// an output file's directory must exist (--plot, --json, --csv); and the excerpts that quote a
// user's text in messages stay short and printable.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.h"
#include "common/text_excerpt.h"
#include "output/output_names.h"
#include "support/temp_dir.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

// The message of the InputError `f` throws, or "" if it throws none.
template <class F>
std::string refusal(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(OutputNames, ANameStaysInsideItsDirectory) {
    for (const char* good : {"patch", "patch.v2", "gear_tooth-0", "a", "..a", "x.."})
        EXPECT_EQ(refusal([&] { check_output_name("--name", good); }), "") << good;
    const auto refused = [](const std::string& name, const std::string& phrase) {
        const std::string m = refusal([&] { check_output_name("--name", name); });
        EXPECT_NE(m.find("--name: expected a file name of letters, digits, '.', '-' and '_'"), std::string::npos) << name << ": " << m;
        EXPECT_NE(m.find(phrase), std::string::npos) << name << ": " << m;
    };
    refused("../../escaped", "got '../../escaped' (a path: no directory separators)");
    refused("/tmp/x", "(a path: no directory separators)");
    refused("a\\b", "(a path: no directory separators)");
    refused("", "got an empty name");
    refused(".", "got '.' (a directory)");
    refused("..", "got '..' (a directory)");
    refused("a b", "got 'a b'");
    refused("tab\there", "got 'tab\\x09here'");
    refused(std::string(kMaxOutputNameBytes + 1, 'n'), "of at most 200 bytes, got 201 bytes");
    EXPECT_EQ(refusal([] { check_output_name("--name", std::string(kMaxOutputNameBytes, 'n')); }), "");
}

TEST(OutputNames, AnOutputFilesDirectoryMustExist) {
    TempDir dir;
    EXPECT_EQ(refusal([&] { check_output_file_directory("--plot", (dir.path / "p.png").string()); }), "");
    EXPECT_EQ(refusal([&] { check_output_file_directory("--plot", "p.png"); }), "");  // the current directory
    const std::string missing = refusal([&] { check_output_file_directory("--plot", (dir.path / "no" / "such" / "p.png").string()); });
    EXPECT_NE(missing.find("--plot: the directory '" + (dir.path / "no" / "such").string() + "'"), std::string::npos) << missing;
    EXPECT_NE(missing.find("does not exist; expected a file in an existing directory"), std::string::npos) << missing;
    EXPECT_FALSE(fs::exists(dir.path / "no"));
    std::ofstream(dir.path / "file") << "x";
    EXPECT_NE(refusal([&] { check_output_file_directory("--json", (dir.path / "file" / "x.json").string()); }).find("is not a directory"),
              std::string::npos);
    EXPECT_NE(refusal([&] { check_output_file_directory("--csv", dir.path.string()); }).find("is a directory; expected a file name"),
              std::string::npos);
    EXPECT_NE(refusal([&] { check_output_file_directory("--csv", ""); }).find("--csv: expected a file name"), std::string::npos);
}

TEST(TextExcerpt, ShortQuotedAndPrintable) {
    EXPECT_EQ(text_excerpt("0.25"), "'0.25'");
    EXPECT_EQ(text_excerpt(std::string("a\x00\x1b\xff'\\", 6)), "'a\\x00\\x1B\\xFF\\'\\\\'");
    EXPECT_EQ(text_excerpt(std::string(100, 'x')), "'" + std::string(kExcerptBytes, 'x') + "'... (100 bytes)");
    EXPECT_TRUE(has_binary_byte(std::string("a\x01", 2)));
    EXPECT_TRUE(has_binary_byte(std::string("\x7f", 1)));
    EXPECT_FALSE(has_binary_byte("time (s),\th\r"));
    EXPECT_FALSE(has_binary_byte("\xC2\xB5m"));  // UTF-8 is text
}

}  // namespace
}  // namespace peensim::testing
