#include "geometry/cad_reader.h"

#include <mutex>

#include "common/input_error.h"
#include "common/loadable_module.h"

namespace peensim {

#if PEENSIM_HAVE_OCCT

bool cad_reading_available() { return true; }

TriangleMesh read_cad_mesh(const std::string& path, const Tessellation& tessellation) {
    static std::once_flag once;
    static const CadModule* module = nullptr;
    std::call_once(once, [] {
        module = static_cast<const CadModule*>(
            load_module_entry("libpeensim_cad.so", "PEENSIM_CAD_MODULE", "peensim_cad_module", "reading STEP/IGES"));
    });
    TriangleMesh mesh;
    std::string problem;
    if (!module->read(path, tessellation, mesh, problem)) throw InputError(SourceLocation{path, 0, 0}, "mesh", problem);
    return mesh;
}

#else

bool cad_reading_available() { return false; }

TriangleMesh read_cad_mesh(const std::string& path, const Tessellation&) {
    throw InputError(SourceLocation{path, 0, 0}, "mesh",
                     "reading STEP/IGES needs OpenCASCADE, which this build of peensim was built without: apt-get install "
                     "libocct-data-exchange-dev libocct-modeling-algorithms-dev and rebuild (cmake finds it), or export the part as STL");
}

#endif

}  // namespace peensim
