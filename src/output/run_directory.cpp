#include "output/run_directory.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <string_view>

#include "common/input_error.h"
#include "output/impact_csv_writer.h"
#include "output/posix_file.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// What the lock file says about the run holding it ("pid 1234, started 2026-11-23 15:30:00 UTC").
std::string holder(int fd) {
    char text[256] = {};
    const ssize_t n = ::pread(fd, text, sizeof(text) - 1, 0);
    std::string s(text, n > 0 ? static_cast<std::size_t>(n) : 0);
    while (!s.empty() && (s.back() == '\n' || s.back() == '\0')) s.pop_back();
    return s.empty() ? "a run that has not written its details yet" : s;
}

}  // namespace

RunDirectoryLock::RunDirectoryLock(const std::string& dir) {
    const std::string path = (fs::path(dir) / kRunLockFileName).string();
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) posix_file::throw_errno("cannot create the run lock", path);
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        const int error = errno;
        const std::string who = holder(fd_);
        ::close(fd_);
        fd_ = -1;
        if (error == EWOULDBLOCK)
            throw InputError(SourceLocation{dir, 0, 0}, "output directory",
                             "in use by another peensim run (" + who + "); wait for it to end, or choose another directory with -o");
        errno = error;
        posix_file::throw_errno("cannot lock", path);
    }
    const std::time_t now = std::time(nullptr);
    char when[64] = {};
    std::strftime(when, sizeof(when), "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
    const std::string text = "pid " + std::to_string(::getpid()) + ", started " + when + "\n";
    // Best effort: the lock itself is what excludes; the text only names the holder.
    if (::ftruncate(fd_, 0) == 0) {
        [[maybe_unused]] const ssize_t written = ::pwrite(fd_, text.data(), text.size(), 0);
    }
}

RunDirectoryLock::~RunDirectoryLock() {
    if (fd_ >= 0) ::close(fd_);  // releases the lock
}

const std::vector<std::string>& run_output_names() {
    static const std::vector<std::string> names{std::string(kImpactCsvFileName),
                                                std::string(kImpactCsvPartialFileName),
                                                "checkpoint.bin",
                                                "summary.json",
                                                "scene.resolved.yaml",
                                                "animation.mp4",
                                                "frames",
                                                "paraview",
                                                kAnalysisDirName,
                                                kAnalysisPartialDirName,
                                                "replicas"};  // a replicas run's spills (app/run/replica_runs.h)
    return names;
}

std::vector<std::string> clear_previous_outputs(const std::string& dir) {
    std::vector<std::string> removed;
    for (const std::string& name : run_output_names()) {
        const fs::path p = fs::path(dir) / name;
        std::error_code ec;
        if (!fs::exists(fs::symlink_status(p, ec))) continue;
        fs::remove_all(p, ec);
        if (ec) throw std::runtime_error("cannot remove the previous run's " + p.string() + ": " + ec.message());
        removed.push_back(name);
    }
    return removed;
}

}  // namespace peensim
