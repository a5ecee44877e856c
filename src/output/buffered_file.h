// An output file written through a fixed buffer, finished atomically: the writers of large
// binary outputs (.vtp files, their scratch arrays) go through it.
//
// The file is created at construction (truncated); finish_as(path) flushes it, fsyncs it (as the
// durability says) and renames it over `path`. A file never finished is removed by the destructor,
// so an exception or a failed write leaves nothing half-written behind.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "output/atomic_file.h"

namespace peensim {

// bytes, the buffer of every BufferedFile.
inline constexpr std::size_t kBufferedFileBytes = std::size_t{1} << 20;

class BufferedFile {
public:
    // Opens `path` with `flags` (O_WRONLY or O_RDWR; O_CREAT | O_TRUNC added). Throws
    // std::runtime_error (path + errno text) when it cannot.
    BufferedFile(std::string path, int flags);
    ~BufferedFile();
    BufferedFile(const BufferedFile&) = delete;
    BufferedFile& operator=(const BufferedFile&) = delete;

    void write(const void* data, std::size_t size);
    template <class T>
    void put(T value) {
        write(&value, sizeof value);
    }
    void flush();

    // Appends the whole content of `source` (flushed here) after this file's bytes: in the kernel
    // with copy_file_range (hundreds of MB for millions of impacts, never through our memory), or
    // by reading and writing where the file system cannot.
    void append_contents_of(BufferedFile& source);

    // Flushes, fsyncs (Durability::power_cut) and renames the file to `final_path`; the file is
    // done then (the destructor leaves it). Throws std::runtime_error; the file is removed then.
    void finish_as(const std::string& final_path, Durability durability = Durability::power_cut);

    std::uint64_t bytes() const { return bytes_; }  // written so far, buffered ones included
    const std::string& path() const { return path_; }

private:
    std::string path_;
    int fd_ = -1;
    std::unique_ptr<char[]> buffer_;
    std::size_t used_ = 0;
    std::uint64_t bytes_ = 0;
};

}  // namespace peensim
