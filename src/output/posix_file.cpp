#include "output/posix_file.h"

#include <fcntl.h>
#include <unistd.h>
#include <cerrno>
#include <cstdio>
#include <stdexcept>
#include <system_error>

namespace peensim::posix_file {

void throw_errno(std::string_view action, const std::string& path) {
    const int err = errno;
    throw std::runtime_error(std::string(action) + " '" + path + "': " + std::generic_category().message(err));
}

int open_or_throw(const std::string& path, int flags, int mode) {
    int fd = -1;
    do {
        fd = ::open(path.c_str(), flags | O_CLOEXEC, mode);
    } while (fd < 0 && errno == EINTR);
    if (fd < 0) throw_errno("cannot open", path);
    return fd;
}

void write_all(int fd, const char* data, std::size_t size, const std::string& path) {
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw_errno("cannot write", path);
        }
        data += n;
        size -= static_cast<std::size_t>(n);
    }
}

void fsync_or_throw(int fd, const std::string& path) {
    if (::fsync(fd) != 0) throw_errno("cannot fsync", path);
}

void close_or_throw(int fd, const std::string& path) {
    // Linux releases the descriptor even when close fails (also on EINTR): never retry.
    if (::close(fd) != 0 && errno != EINTR) throw_errno("cannot close", path);
}

void fsync_directory(const std::string& dir) {
    const int fd = open_or_throw(dir, O_RDONLY | O_DIRECTORY);
    if (::fsync(fd) != 0) {
        const int err = errno;
        ::close(fd);
        errno = err;
        throw_errno("cannot fsync directory", dir);
    }
    ::close(fd);
}

void rename_or_throw(const std::string& from, const std::string& to) {
    if (std::rename(from.c_str(), to.c_str()) != 0) {
        throw_errno("cannot rename to '" + to + "'", from);
    }
}

std::string parent_directory(const std::string& path) {
    const auto slash = path.find_last_of('/');
    if (slash == std::string::npos) return ".";
    if (slash == 0) return "/";
    return path.substr(0, slash);
}

}  // namespace peensim::posix_file
