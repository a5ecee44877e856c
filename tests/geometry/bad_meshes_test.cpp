// The catalogue of hostile mesh files (tests/meshes_bad): each is refused at once (well under a
// second, no large allocation) with an input error naming the file and what is wrong, never a
// hang or a crash. The first case was found by a user: a 291-byte PLY whose header claims 1e9
// vertices made the reader allocate ~12 GB and hang.
#include <gtest/gtest.h>

#include <chrono>
#include <ostream>
#include <string>

#include "common/input_error.h"
#include "geometry/mesh_loader.h"

namespace peensim {
namespace {

const std::string bad_dir = std::string(PEENSIM_SOURCE_DIR) + "/tests/meshes_bad";

struct BadMesh {
    const char* file;
    const char* expected;  // a phrase of the message
};

// gtest's own printer would dump the case's bytes, unset ones among them (valgrind reports them
// as uninitialised at every start of the test binary).
void PrintTo(const BadMesh& b, std::ostream* os) { *os << b.file; }

const BadMesh catalogue[] = {
    {"ply_billion_vertices.ply", "the PLY header declares 1000000000 vertex elements, but the file (291 bytes) can hold at most"},
    {"ply_ascii_face_count.ply", "declares 4000000000 face elements"},
    // Found by fuzzing under AddressSanitizer: the reader allocated 28 GB for one list.
    {"ply_list_property_twice.ply", "PLY header line 9: property 'vertex_indices' twice in element 'face'"},
    {"ply_ascii_list_too_long.ply", "PLY line 16: a list of '2000000000' values in element 'face' with 3 values left on the line"},
    {"stl_count_beyond_file.stl", "the binary STL declares 100000 facets, but the file (134 bytes) holds at most 1"},
    // Found by a tester: the reader read "2x" as 2, a part silently of other coordinates.
    {"obj_number_with_a_word.obj", "obj_number_with_a_word.obj:3:8: mesh: OBJ: expected a finite number in 'v', got '2x'"},
    {"stl_ascii_number_with_a_word.stl",
     "stl_ascii_number_with_a_word.stl:5:18: mesh: ASCII STL: expected a finite number in 'vertex', got '2x'"},
#if PEENSIM_HAVE_OCCT
    // Found by a tester: tests/app/new_scene/rod.step with one entity of a type OpenCASCADE does
    // not know, or with one that others name deleted, crashed peensim (SIGSEGV in OpenCASCADE's
    // STEP reader); it reads in a child process now. The signal is SIGSEGV, or SIGABRT under
    // AddressSanitizer, whose handler reports the crash in the child and aborts it.
    {"step_unknown_entity_type.step", "OpenCASCADE crashed reading the file (signal "},
    {"step_entity_deleted.step", "OpenCASCADE crashed reading the file (signal "},
#endif
};

class GeometryBadMeshes : public ::testing::TestWithParam<BadMesh> {};

TEST_P(GeometryBadMeshes, IsRefusedAtOnceNamingTheFile) {
    const BadMesh& bad = GetParam();
    const std::string path = bad_dir + "/" + bad.file;
    const auto start = std::chrono::steady_clock::now();
    try {
        load_mesh(path, 1e-3);
        ADD_FAILURE() << bad.file << " was loaded";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where().file, path);
        EXPECT_EQ(e.field(), "mesh");
        EXPECT_NE(std::string(e.what()).find(bad.expected), std::string::npos) << e.what();
    }
    // Not a timed test of speed: a refusal that took this long would have read the file's claims.
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

INSTANTIATE_TEST_SUITE_P(Catalogue, GeometryBadMeshes, ::testing::ValuesIn(catalogue), [](const ::testing::TestParamInfo<BadMesh>& info) {
    std::string name = info.param.file;
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
});

}  // namespace
}  // namespace peensim
