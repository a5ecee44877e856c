#include "geometry/cad_reader.h"

#include "common/input_error.h"

#if PEENSIM_HAVE_OCCT
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "common/byte_stream.h"
#include "common/loadable_module.h"
#endif

namespace peensim {

#if PEENSIM_HAVE_OCCT

namespace {

// The child's answer through the pipe: a kind, then the mesh or the message.
enum class Answer : std::uint8_t { mesh = 0, input_problem = 1, failure = 2 };

// The mesh's fields in order (common/byte_stream.h).
std::string encode(const TriangleMesh& mesh) {
    ByteWriter b;
    b.put(Answer::mesh);
    std::vector<std::array<double, 3>> vertices;  // m
    vertices.reserve(mesh.vertices.size());
    for (const Vec3& v : mesh.vertices) vertices.push_back({v.x(), v.y(), v.z()});
    b.put_vector(vertices);
    b.put_vector(mesh.triangles);
    b.put_vector(mesh.source_facet);
    b.put<std::uint64_t>(mesh.group_names.size());
    for (const std::string& name : mesh.group_names) b.put_string(name);
    b.put_vector(mesh.group_of_triangle);
    b.put<std::uint64_t>(mesh.dropped_degenerate_facets);
    b.put_string(mesh.declared_unit);
    return b.bytes();
}

std::string encode_message(Answer kind, const std::string& message) {
    ByteWriter b;
    b.put(kind);
    b.put_string(message);
    return b.bytes();
}

// In the child: the module, or null with why this installation cannot read any part, as a build
// without OpenCASCADE cannot (the scene's mesh is refused: exit 2; a sweep does not run it again).
const CadModule* load_cad_module(std::string& problem) {
    try {
        return static_cast<const CadModule*>(
            load_module_entry("libpeensim_cad.so", "PEENSIM_CAD_MODULE", "peensim_cad_module", "reading STEP/IGES"));
    } catch (const std::exception& e) {
        problem = std::string(e.what()) + "; or export the part as STL";
        return nullptr;
    }
}

// In the child: loads the module, reads the file unless `load_only`, writes the answer; never
// returns.
[[noreturn]] void read_in_child(int out, const std::string& path, const Tessellation& tessellation, bool load_only) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // dies with the process that waits for it
    std::string answer;
    std::string problem;
    const CadModule* module = load_cad_module(problem);
    if (module == nullptr) answer = encode_message(Answer::input_problem, problem);
    if (module != nullptr && load_only) answer = encode(TriangleMesh{});
    if (module != nullptr && !load_only) {
        try {
            TriangleMesh mesh;
            std::string problem;
            answer = module->read(path, tessellation, mesh, problem) ? encode(mesh) : encode_message(Answer::input_problem, problem);
        } catch (const std::exception& e) {
            answer = encode_message(Answer::failure, e.what());
        } catch (...) {
            answer = encode_message(Answer::failure, "the STEP/IGES reader failed");
        }
    }
    std::size_t written = 0;
    while (written < answer.size()) {
        const ssize_t n = ::write(out, answer.data() + written, answer.size() - written);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) ::_exit(1);
        written += static_cast<std::size_t>(n);
    }
    ::_exit(0);  // no destructors, no flushing of the parent's buffers
}

}  // namespace

bool cad_reading_available() { return true; }

// OpenCASCADE reads in a child process: on some damaged files (an entity that another names
// deleted, or of a type it does not know) its STEP reader dereferences a null handle and the
// process dies of SIGSEGV, which no C++ handler catches (OpenCASCADE converts signals into
// exceptions only when built for it, and Debian's is not). The child dies instead, and the file is
// an input error. The module is loaded in the child only, so the process that asks never maps
// OpenCASCADE. fork() copies only the calling thread: the child runs the loader, the module and
// write() only, and glibc keeps malloc and the loader usable in it (meshes are loaded before a run
// starts its threads; a Python caller's threads are not touched by the child).
namespace {

// The child's answer to read_in_child(path, tessellation, load_only), or the InputError of a
// child that died.
std::string answer_of_child(const std::string& path, const Tessellation& tessellation, bool load_only) {
    int pipe_ends[2];
    if (::pipe(pipe_ends) != 0) throw std::runtime_error("reading " + path + ": cannot make a pipe: " + std::strerror(errno));
    const pid_t child = ::fork();
    if (child < 0) {
        ::close(pipe_ends[0]);
        ::close(pipe_ends[1]);
        throw std::runtime_error("reading " + path + ": cannot start the STEP/IGES reader: " + std::strerror(errno));
    }
    if (child == 0) {
        ::close(pipe_ends[0]);
        read_in_child(pipe_ends[1], path, tessellation, load_only);
    }
    ::close(pipe_ends[1]);
    std::string answer;
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(pipe_ends[0], buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        answer.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(pipe_ends[0]);
    int status = 0;
    while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {}
    if (WIFSIGNALED(status)) {
        const int signal = WTERMSIG(status);
        throw InputError(SourceLocation{path, 0, 0}, "mesh",
                         "OpenCASCADE crashed reading the file (signal " + std::to_string(signal) + ", " + ::strsignal(signal) +
                             "): it is damaged, or holds entities OpenCASCADE cannot read; export it again (STEP AP214 or AP203, "
                             "or STL)");
    }
    if (answer.empty()) throw std::runtime_error("reading " + path + ": the STEP/IGES reader ended without an answer");
    return answer;
}

}  // namespace

void require_cad_reading(const std::string& path) {
    // One child per value of the module's variable (a sweep checks every variant; a Python session
    // may set the variable between two calls): whether the module loads depends on it alone.
    static std::mutex guard;
    static std::map<std::string, std::string> answers;
    const char* chosen = std::getenv("PEENSIM_CAD_MODULE");
    const std::string key = chosen != nullptr ? chosen : "";
    std::string answer;
    {
        const std::lock_guard<std::mutex> lock(guard);
        if (const auto it = answers.find(key); it != answers.end()) answer = it->second;
    }
    if (answer.empty()) {
        answer = answer_of_child(path, Tessellation{}, true);
        const std::lock_guard<std::mutex> lock(guard);
        answers.emplace(key, answer);
    }
    ByteReader r(answer, "loading the STEP/IGES reader: its answer");
    if (r.get<Answer>() == Answer::input_problem) throw InputError(SourceLocation{path, 0, 0}, "mesh", r.get_string());
}

TriangleMesh read_cad_mesh(const std::string& path, const Tessellation& tessellation) {
    const std::string answer = answer_of_child(path, tessellation, false);
    ByteReader r(answer, "reading " + path + ": the STEP/IGES reader's answer");
    switch (r.get<Answer>()) {
        case Answer::input_problem: throw InputError(SourceLocation{path, 0, 0}, "mesh", r.get_string());
        case Answer::failure: throw std::runtime_error(path + ": " + r.get_string());
        case Answer::mesh: break;
    }
    TriangleMesh mesh;
    for (const std::array<double, 3>& v : r.get_vector<std::array<double, 3>>()) mesh.vertices.emplace_back(v[0], v[1], v[2]);
    mesh.triangles = r.get_vector<std::array<int, 3>>();
    mesh.source_facet = r.get_vector<int>();
    const auto groups = r.get<std::uint64_t>();
    for (std::uint64_t g = 0; g < groups; ++g) mesh.group_names.push_back(r.get_string());
    mesh.group_of_triangle = r.get_vector<int>();
    mesh.dropped_degenerate_facets = static_cast<std::size_t>(r.get<std::uint64_t>());
    mesh.declared_unit = r.get_string();
    return mesh;
}

#else

bool cad_reading_available() { return false; }

void require_cad_reading(const std::string& path) {
    throw InputError(SourceLocation{path, 0, 0}, "mesh",
                     "reading STEP/IGES needs OpenCASCADE, which this build of peensim was built without: apt-get install "
                     "libocct-data-exchange-dev libocct-modeling-algorithms-dev and rebuild (cmake finds it), or export the part as STL");
}

TriangleMesh read_cad_mesh(const std::string& path, const Tessellation&) {
    require_cad_reading(path);
    return {};
}

#endif

}  // namespace peensim
