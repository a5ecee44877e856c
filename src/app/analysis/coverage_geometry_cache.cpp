#include "app/analysis/coverage_geometry_cache.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string_view>
#include <thread>
#include <vector>

#include "common/byte_stream.h"
#include "common/fnv_hash.h"
#include "output/atomic_file.h"
#include "scene/resolved_writer.h"
#include "scene/shot_mix.h"

namespace peensim {

namespace fs = std::filesystem;

namespace {

// The file's first bytes, and its layout's version: a change of layout is another version (read
// as "not this layout", computed again).
constexpr std::string_view kMagic = "peensim coverage geometry\n";
constexpr std::uint32_t kLayout = 1;

std::string file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return {};
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The binaries that hold this code, hashed once: another build may compute the geometry
// otherwise. The program itself (/proc/self/exe), and the shared library this code is in when it
// is not the program (the Python module's, loaded by python3), named by an absolute path.
std::uint64_t this_build_hash() {
    static const std::uint64_t hash = [] {
        const std::string program = file_bytes("/proc/self/exe");
        if (program.empty()) throw std::runtime_error("cannot read this program's own binary to key the coverage geometry cache");
        std::uint64_t h = fnv1a64(program);
        Dl_info info{};
        std::error_code error;
        if (::dladdr(reinterpret_cast<const void*>(&this_build_hash), &info) != 0 && info.dli_fname != nullptr &&
            info.dli_fname[0] == '/' && !fs::equivalent(info.dli_fname, "/proc/self/exe", error))
            h = fnv1a64(file_bytes(info.dli_fname), h);
        return h;
    }();
    return hash;
}

class KeyHash {
public:
    template <class T>
    void add(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        h_ = fnv1a64(std::string_view(reinterpret_cast<const char*>(&v), sizeof(T)), h_);
    }
    template <class T>
    void add_vector(const std::vector<T>& v) {
        add<std::uint64_t>(v.size());
        if (!v.empty()) h_ = fnv1a64(std::string_view(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T)), h_);
    }
    void add_text(std::string_view s) {
        add<std::uint64_t>(s.size());
        h_ = fnv1a64(s, h_);
    }
    std::uint64_t value() const { return h_; }

private:
    std::uint64_t h_ = kFnvOffsetBasis;
};

void add_vec(KeyHash& key, const Vec3& v) {
    for (int k = 0; k < 3; ++k) key.add(v[k]);
}

}  // namespace

std::uint64_t coverage_geometry_key(const Model& model, std::size_t ci, double yield_pa) {
    KeyHash key;
    key.add_text(kMagic);
    key.add(kLayout);
    key.add(this_build_hash());
    // The assembly at t = 0: what the reach probes and the cavity read of every component.
    key.add<std::uint64_t>(model.components.size());
    const SimTime t0;
    for (const Component& c : model.components) {
        const TriangleMesh& mesh = *c.mesh;
        key.add_vector(mesh.vertices);
        key.add_vector(mesh.triangles);
        key.add_vector(mesh.group_of_triangle);
        key.add<std::uint64_t>(mesh.group_names.size());
        for (const std::string& g : mesh.group_names) key.add_text(g);
        const Pose pose = c.kinematics.pose(t0);
        for (int r = 0; r < 3; ++r) add_vec(key, pose.rotation.row(r).transpose());
        add_vec(key, pose.translation);
        add_vec(key, c.kinematics.axis);
        key.add<std::uint8_t>(c.solid ? 1 : 0);
    }
    key.add(model.sonotrode);
    add_vec(key, model.gravity_m_per_s2);
    // The part and its regions.
    key.add<std::uint64_t>(ci);
    key.add(yield_pa);
    const SceneDescription& scene = model.description;
    key.add<std::uint64_t>(scene.components[ci].regions.size());
    for (const RegionDesc& r : scene.components[ci].regions) key.add_text(resolved_region_text(r));
    // The shot: the map's resolution and the dents' sizes follow its sizes and density, the reach
    // its smallest radius.
    key.add(smallest_diameter_m(scene.shot));
    key.add(largest_diameter_m(scene.shot));
    key.add(scene.shot.density_kg_per_m3);
    key.add(model.min_shot_radius_m);
    return key.value();
}

std::string coverage_geometry_file(const std::string& dir, std::uint64_t key) {
    char name[48];
    std::snprintf(name, sizeof name, "coverage-%016llx.bin", static_cast<unsigned long long>(key));
    return (fs::path(dir) / name).string();
}

bool load_coverage_geometry(const std::string& dir, std::uint64_t key, const TriangleMesh& mesh, const RegionSet& regions,
                            SampleClasses& classes, UnreachableFindings& unreachable, std::string& why) {
    why.clear();
    const std::string path = coverage_geometry_file(dir, key);
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (!fs::exists(status)) return false;
    // Only a regular file is read: a folder or a FIFO under the entry's name would throw or block.
    if (!fs::is_regular_file(status)) {
        why = path + ": not a regular file";
        return false;
    }
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        why = path + ": cannot be read (" + std::strerror(errno) + ")";
        return false;
    }
    std::string bytes;
    try {
        bytes.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
        ByteReader in(bytes, path);
        if (in.take(kMagic.size()) != kMagic || in.get<std::uint32_t>() != kLayout) in.fail("not a coverage geometry of this layout");
        if (in.get<std::uint64_t>() != key) in.fail("another key than its name's");
        const auto payload_size = in.get<std::uint64_t>();
        const std::string_view payload = in.take(payload_size);
        if (in.get<std::uint64_t>() != fnv1a64(payload) || !in.at_end())
            in.fail("its checksum does not match its bytes (altered or cut short)");
        ByteReader p(payload, path);
        SampleClasses c = SampleClasses::read_bytes(p, mesh.triangle_count(), regions.size());
        UnreachableFindings u;
        u.shot_diameter_m = p.get<double>();
        u.whole = p.get<UnreachableArea>();
        u.regions = p.get_vector<UnreachableArea>();
        u.triangle_share = p.get_vector<double>();
        if (u.regions.size() != regions.size() || u.triangle_share.size() != mesh.triangle_count() || !p.at_end())
            p.fail("not of this part");
        classes = std::move(c);
        unreachable = std::move(u);
        // Read now: the cap drops the entries read longest ago (a read-only folder keeps its times).
        fs::last_write_time(path, fs::file_time_type::clock::now(), error);
        return true;
    } catch (const std::exception& e) {  // the reader's, or the stream's on a read error
        why = e.what();
        return false;
    }
}

CoverageGeometryLock::CoverageGeometryLock(const std::string& dir, std::uint64_t key, const std::function<void()>& waiting,
                                           double patience_s) {
    const auto start = std::chrono::steady_clock::now();
    std::error_code ignored;
    fs::create_directories(dir, ignored);
    std::string path = coverage_geometry_file(dir, key);
    path.replace(path.size() - 4, 4, ".lock");
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) return;
    while (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        if (errno != EWOULDBLOCK && errno != EINTR) {  // no lock to be had here: hold nothing
            ::close(fd_);
            fd_ = -1;
            return;
        }
        try {
            waiting();
        } catch (...) {
            ::close(fd_);
            throw;
        }
        waited_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (waited_s_ >= patience_s) {  // the run holding it is stuck or far slower: go on without it
            ::close(fd_);
            fd_ = -1;
            gave_up_ = true;
            return;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
}

CoverageGeometryLock::~CoverageGeometryLock() {
    if (fd_ >= 0) ::close(fd_);  // releases the lock
}

namespace {

// Removes the entries of `dir` but `kept` read or written longest ago while they hold more than
// cap_bytes, and the temporaries of runs killed while writing one (an hour old). Runs that evict
// at once may remove the same file twice (the second removal finds nothing) or a file another run
// is about to read (which then computes it again).
void evict_oldest(const std::string& dir, const std::string& kept, std::uintmax_t cap_bytes) {
    struct Entry {
        fs::file_time_type written;
        std::uintmax_t bytes;
        fs::path path;
    };
    std::vector<Entry> entries;
    std::uintmax_t total = 0;
    std::error_code error;
    for (const fs::directory_entry& e : fs::directory_iterator(dir, error)) {
        const std::string name = e.path().filename().string();
        if (name.rfind("coverage-", 0) != 0) continue;
        if (name.find(".bin.") != std::string::npos) {  // coverage-<key>.bin.<pid>[.tmp]: a write in progress, or abandoned
            const fs::file_time_type written = e.last_write_time(error);
            if (!error && written < fs::file_time_type::clock::now() - std::chrono::hours(1)) fs::remove(e.path(), error);
            continue;
        }
        if (e.path().extension() != ".bin") continue;
        const std::uintmax_t bytes = e.file_size(error);
        if (error) continue;
        total += bytes;
        if (e.path() != fs::path(kept)) entries.push_back({e.last_write_time(error), bytes, e.path()});
    }
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.written < b.written; });
    for (const Entry& e : entries) {
        if (total <= cap_bytes) break;
        fs::remove(e.path, error);
        total -= e.bytes;
    }
}

}  // namespace

void store_coverage_geometry(const std::string& dir, std::uint64_t key, const SampleClasses& classes,
                             const UnreachableFindings& unreachable, std::uintmax_t cap_bytes) {
    ByteWriter payload;
    classes.write_bytes(payload);
    payload.put(unreachable.shot_diameter_m);
    payload.put(unreachable.whole);
    payload.put_vector(unreachable.regions);
    payload.put_vector(unreachable.triangle_share);
    ByteWriter file;
    file.put_raw(kMagic);
    file.put(kLayout);
    file.put(key);
    file.put_string(payload.bytes());
    file.put(fnv1a64(payload.bytes()));
    std::error_code ignored;
    fs::create_directories(dir, ignored);
    const std::string path = coverage_geometry_file(dir, key);
    // A name of this process's first: two runs storing the same entry at once never share a
    // temporary file; the rename leaves one whole file either way.
    const std::string own = path + "." + std::to_string(::getpid());
    write_file_atomically(own, file.bytes(), Durability::process_crash);
    std::error_code error;
    fs::rename(own, path, error);
    if (error) {  // a folder under the entry's name, say: the run goes on without keeping it
        std::error_code ignored;
        fs::remove(own, ignored);
        throw fs::filesystem_error("cannot keep it", own, path, error);
    }
    evict_oldest(dir, path, cap_bytes);
}

}  // namespace peensim
