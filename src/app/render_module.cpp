#include "app/render_module.h"

#include <mutex>

#include "common/loadable_module.h"

namespace peensim {

namespace {

const RenderModule* load() {
    return static_cast<const RenderModule*>(
        load_module_entry("libpeensim_render.so", "PEENSIM_RENDER_MODULE", "peensim_render_module", "rendering"));
}

}  // namespace

const RenderModule& render_module() {
    static std::once_flag once;
    static const RenderModule* module = nullptr;
    std::call_once(once, [] { module = load(); });
    return *module;
}

}  // namespace peensim
