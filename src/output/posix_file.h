// Thin wrappers over the POSIX file calls the writers need (write, fsync, rename, truncate),
// each throwing std::runtime_error that names the path and the errno text, so a full disk
// or a missing directory reads as "impacts.csv.partial: No space left on device".
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace peensim::posix_file {

// "<action> '<path>': <errno text>" for the current errno.
[[noreturn]] void throw_errno(std::string_view action, const std::string& path);

// open(2) with O_CLOEXEC added; throws on failure.
int open_or_throw(const std::string& path, int flags, int mode = 0644);

// Writes all of [data, data + size), retrying on EINTR and short writes.
void write_all(int fd, const char* data, std::size_t size, const std::string& path);

void fsync_or_throw(int fd, const std::string& path);

// close(2); a failed close can be a lost delayed write error, so it throws too.
void close_or_throw(int fd, const std::string& path);

// Makes a rename or a file creation in `dir` durable (fsync of the directory itself).
void fsync_directory(const std::string& dir);

void rename_or_throw(const std::string& from, const std::string& to);

// Directory part of a path ("." when there is none), for fsync_directory.
std::string parent_directory(const std::string& path);

}  // namespace peensim::posix_file
