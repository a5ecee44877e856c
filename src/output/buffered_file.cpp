#include "output/buffered_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "output/posix_file.h"

namespace peensim {

BufferedFile::BufferedFile(std::string path, int flags)
    : path_(std::move(path)), fd_(posix_file::open_or_throw(path_, flags | O_CREAT | O_TRUNC)), buffer_(new char[kBufferedFileBytes]) {}

BufferedFile::~BufferedFile() {
    if (fd_ >= 0) {
        ::close(fd_);
        ::unlink(path_.c_str());
    }
}

void BufferedFile::write(const void* data, std::size_t size) {
    const char* bytes = static_cast<const char*>(data);
    if (size >= kBufferedFileBytes) {  // large blocks skip the buffer
        flush();
        posix_file::write_all(fd_, bytes, size, path_);
        bytes_ += size;
        return;
    }
    if (used_ + size > kBufferedFileBytes) flush();
    std::memcpy(buffer_.get() + used_, bytes, size);
    used_ += size;
    bytes_ += size;
}

void BufferedFile::flush() {
    posix_file::write_all(fd_, buffer_.get(), used_, path_);
    used_ = 0;
}

void BufferedFile::append_contents_of(BufferedFile& source) {
    source.flush();
    flush();
    off64_t from = 0;
    for (;;) {
        const ssize_t n = ::copy_file_range(source.fd_, &from, fd_, nullptr, std::size_t{1} << 30, 0);
        if (n > 0) {
            bytes_ += static_cast<std::uint64_t>(n);
            continue;
        }
        if (n == 0) return;
        if (errno == EINTR) continue;
        if (errno == EXDEV || errno == ENOSYS || errno == EINVAL || errno == EOPNOTSUPP) break;
        posix_file::throw_errno("cannot copy", source.path_);
    }
    if (::lseek(source.fd_, from, SEEK_SET) < 0) posix_file::throw_errno("cannot seek", source.path_);
    for (;;) {
        const ssize_t n = ::read(source.fd_, buffer_.get(), kBufferedFileBytes);
        if (n < 0) {
            if (errno == EINTR) continue;
            posix_file::throw_errno("cannot read", source.path_);
        }
        if (n == 0) break;
        posix_file::write_all(fd_, buffer_.get(), static_cast<std::size_t>(n), path_);
        bytes_ += static_cast<std::uint64_t>(n);
    }
}

void BufferedFile::finish_as(const std::string& final_path, Durability durability) {
    flush();
    if (durability == Durability::power_cut) posix_file::fsync_or_throw(fd_, path_);
    const int fd = std::exchange(fd_, -1);
    try {
        posix_file::close_or_throw(fd, path_);
        posix_file::rename_or_throw(path_, final_path);
    } catch (...) {
        ::unlink(path_.c_str());
        throw;
    }
    if (durability == Durability::power_cut) posix_file::fsync_directory(posix_file::parent_directory(final_path));
}

}  // namespace peensim
