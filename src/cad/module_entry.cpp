// The entry point of libpeensim_cad.so (see geometry/cad_reader.h): the STEP and IGES reader,
// handed to a peensim that loaded this module on demand. An input problem crosses back as its
// message, not as an InputError: the module's copy of that type is not the loader's.
#include "cad/cad_tessellation.h"
#include "common/input_error.h"

namespace {

bool read(const std::string& path, const peensim::Tessellation& tessellation, peensim::TriangleMesh& mesh, std::string& problem) {
    try {
        mesh = peensim::tessellate_cad_file(path, tessellation);
        return true;
    } catch (const peensim::InputError& e) {
        problem = e.problem();
        return false;
    }
}

const peensim::CadModule kModule{&read};

}  // namespace

extern "C" __attribute__((visibility("default"))) const peensim::CadModule* peensim_cad_module() { return &kModule; }
