#include "app/render_module.h"

#include <dlfcn.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <system_error>

namespace fs = std::filesystem;

namespace peensim {

namespace {

constexpr const char* kModuleFile = "libpeensim_render.so";
constexpr const char* kEntrySymbol = "peensim_render_module";

const RenderModule* load() {
    std::vector<std::string> candidates;
    if (const char* path = std::getenv("PEENSIM_RENDER_MODULE")) candidates.emplace_back(path);
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        candidates.push_back((exe.parent_path() / kModuleFile).string());
        candidates.push_back((exe.parent_path().parent_path() / kModuleFile).string());
    }
    candidates.emplace_back(kModuleFile);  // the library search path
    std::string tried;
    for (const std::string& c : candidates) {
        const bool is_path = c.find('/') != std::string::npos;
        if (is_path && !fs::exists(c, ec)) {
            tried += "\n  " + c + " (no such file)";
            continue;
        }
        void* handle = ::dlopen(c.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            tried += "\n  " + c + ": " + ::dlerror();
            continue;
        }
        using Entry = const RenderModule* (*)();
        const auto entry = reinterpret_cast<Entry>(::dlsym(handle, kEntrySymbol));
        if (!entry) {
            tried += "\n  " + c + ": no symbol " + kEntrySymbol;
            continue;
        }
        return entry();  // the module stays loaded for the life of the process
    }
    throw std::runtime_error(std::string("rendering needs ") + kModuleFile + " (built with peensim), not found:" + tried +
                             "\nset PEENSIM_RENDER_MODULE to its path");
}

}  // namespace

const RenderModule& render_module() {
    static std::once_flag once;
    static const RenderModule* module = nullptr;
    std::call_once(once, [] { module = load(); });
    return *module;
}

}  // namespace peensim
