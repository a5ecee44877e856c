#include "common/loadable_module.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <vector>

namespace fs = std::filesystem;

namespace peensim {

const void* load_module_entry(const std::string& file, const char* env_var, const char* entry_symbol, const std::string& what) {
    std::vector<std::string> candidates;
    std::error_code ec;
    // Set (not empty): the one the user chose, alone. Falling back to another module when it does
    // not load would run a build they did not ask for, without a word.
    const char* chosen = std::getenv(env_var);
    if (chosen != nullptr && *chosen != '\0' && std::string_view(chosen).find_first_not_of(" \t\n") == std::string_view::npos)
        throw std::runtime_error(what + " needs " + file + " (built with peensim); " + env_var + " is set to blanks only (\"" + chosen +
                                 "\"): set it to the module's path, or unset it (peensim then looks beside itself)");
    if (chosen != nullptr && *chosen != '\0') {
        candidates.emplace_back(chosen);
    } else {
        const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
        if (!ec) {
            candidates.push_back((exe.parent_path() / file).string());
            candidates.push_back((exe.parent_path().parent_path() / file).string());
        }
        candidates.push_back(file);  // the library search path
    }
    std::string tried;
    for (const std::string& c : candidates) {
        const bool is_path = c.find('/') != std::string::npos;
        if (is_path && !fs::exists(c, ec)) {
            tried += "\n  " + c + " (no such file)";
            continue;
        }
        void* handle = ::dlopen(c.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const std::string why = ::dlerror();  // glibc's names the file first, most often
            tried += "\n  " + (why.rfind(c + ": ", 0) == 0 ? why : c + ": " + why);
            continue;
        }
        using Entry = const void* (*)();
        const auto entry = reinterpret_cast<Entry>(::dlsym(handle, entry_symbol));
        if (!entry) {
            tried += "\n  " + c + ": no symbol " + entry_symbol;
            continue;
        }
        return entry();
    }
    // "not found" would be wrong for a file that is there but is not the module (each line says why).
    if (chosen != nullptr && *chosen != '\0')
        throw std::runtime_error(what + " needs " + file + " (built with peensim), which " + env_var + " does not name:" + tried +
                                 "\nset " + env_var + " to its path, or unset it (peensim then looks beside itself)");
    throw std::runtime_error(what + " needs " + file + " (built with peensim), which none of these is:" + tried + "\nset " + env_var +
                             " to its path");
}

}  // namespace peensim
