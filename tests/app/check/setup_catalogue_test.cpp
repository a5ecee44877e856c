// The catalogue of setup mistakes (tests/scenes_setup/*.yaml, issue 11 "A setup you can trust"):
// one scene file per mistake users made that used to pass `check` and run with exit 0, and per
// valid scene that used to be refused. Each file states in its header what `peensim check` must
// do with it:
//   # expect-exit: N          exit code of `check` (0 valid, 2 refused)
//   # expect-strict-exit: N   exit code of `check --strict` (default: the same as expect-exit)
//   # expect: TEXT            a phrase the output must contain (any number of these)
//   # expect-none: TEXT       a phrase it must not contain
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/check/check_job.h"
#include "app/run/run_job.h"

namespace peensim {
namespace {

namespace fs = std::filesystem;

const fs::path kCatalogue = fs::path(PEENSIM_SOURCE_DIR) / "tests" / "scenes_setup";

struct Expectation {
    std::string file;
    int exit = -1;
    int strict_exit = -1;
    std::vector<std::string> present, absent;
};

void PrintTo(const Expectation& e, std::ostream* os) { *os << e.file; }

Expectation read_expectation(const fs::path& path) {
    Expectation e;
    e.file = path.filename().string();
    std::ifstream in(path);
    std::string line;
    const auto value = [&](const std::string& key, std::string& out) {
        const std::string prefix = "# " + key + ": ";
        if (line.rfind(prefix, 0) != 0) return false;
        out = line.substr(prefix.size());
        return true;
    };
    while (std::getline(in, line) && line.rfind('#', 0) == 0) {
        std::string v;
        if (value("expect-exit", v))
            e.exit = std::stoi(v);
        else if (value("expect-strict-exit", v))
            e.strict_exit = std::stoi(v);
        else if (value("expect", v))
            e.present.push_back(v);
        else if (value("expect-none", v))
            e.absent.push_back(v);
    }
    if (e.strict_exit < 0) e.strict_exit = e.exit;
    return e;
}

std::vector<Expectation> catalogue() {
    std::vector<Expectation> v;
    for (const fs::directory_entry& entry : fs::directory_iterator(kCatalogue))
        if (entry.path().extension() == ".yaml") v.push_back(read_expectation(entry.path()));
    std::sort(v.begin(), v.end(), [](const Expectation& a, const Expectation& b) { return a.file < b.file; });
    return v;
}

class SetupCatalogue : public ::testing::TestWithParam<Expectation> {};

TEST_P(SetupCatalogue, CheckSaysWhatTheFileExpects) {
    const Expectation& e = GetParam();
    ASSERT_GE(e.exit, 0) << e.file << ": no '# expect-exit:' line";
    ASSERT_FALSE(e.present.empty()) << e.file << ": no '# expect:' line";
    const std::string path = (kCatalogue / e.file).string();
    std::ostringstream out, err;
    EXPECT_EQ(check_job(path, {}, false, out, err), e.exit) << err.str();
    const std::string text = err.str() + out.str();
    for (const std::string& phrase : e.present) EXPECT_NE(text.find(phrase), std::string::npos) << "'" << phrase << "' in:\n" << text;
    for (const std::string& phrase : e.absent) EXPECT_EQ(text.find(phrase), std::string::npos) << "'" << phrase << "' in:\n" << text;
    // Errors name the file and the line of the component, never an internal class.
    if (e.exit == kExitInputError) {
        EXPECT_NE(text.find(e.file + ":"), std::string::npos) << text;
    }
    std::ostringstream strict_out, strict_err;
    EXPECT_EQ(check_job(path, {}, true, strict_out, strict_err), e.strict_exit) << strict_err.str();
}

INSTANTIATE_TEST_SUITE_P(Files, SetupCatalogue, ::testing::ValuesIn(catalogue()), [](const ::testing::TestParamInfo<Expectation>& info) {
    std::string name = info.param.file.substr(0, info.param.file.size() - 5);
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
});

}  // namespace
}  // namespace peensim
