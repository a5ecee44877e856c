#include "output/output_names.h"

#include <filesystem>
#include <system_error>

#include "common/input_error.h"
#include "common/text_excerpt.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

bool name_character(char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '_';
}

}  // namespace

bool is_output_name(const std::string& name) {
    if (name.empty() || name.size() > kMaxOutputNameBytes || name == "." || name == "..") return false;
    for (const char c : name)
        if (!name_character(c)) return false;
    return true;
}

void check_output_name(const std::string& option, const std::string& name) {
    const std::string expected = "expected a file name of letters, digits, '.', '-' and '_' (it stays inside the output directory)";
    if (name.empty()) throw InputError({option}, "", expected + ", got an empty name");
    if (name.size() > kMaxOutputNameBytes)
        throw InputError(
            {option}, "",
            expected + " of at most " + std::to_string(kMaxOutputNameBytes) + " bytes, got " + std::to_string(name.size()) + " bytes");
    if (name == "." || name == "..") throw InputError({option}, "", expected + ", got " + text_excerpt(name) + " (a directory)");
    for (const char c : name) {
        if (name_character(c)) continue;
        const std::string what = c == '/' || c == '\\' ? " (a path: no directory separators)" : "";
        throw InputError({option}, "", expected + ", got " + text_excerpt(name) + what);
    }
}

void check_output_file_directory(const std::string& option, const std::string& path) {
    if (path.empty()) throw InputError({option}, "", "expected a file name, got an empty one");
    const fs::path p(path);
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::exists(dir, ec))
        throw InputError({option}, "",
                         "the directory " + text_excerpt(dir.string()) + " of " + text_excerpt(path) +
                             " does not exist; expected a file in an existing directory (peensim creates none for it)");
    if (!fs::is_directory(dir, ec))
        throw InputError({option}, "", text_excerpt(dir.string()) + " is not a directory; expected a file in a directory");
    if (!p.has_filename() || fs::is_directory(p, ec))
        throw InputError({option}, "", text_excerpt(path) + " is a directory; expected a file name");
}

}  // namespace peensim
