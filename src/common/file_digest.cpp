#include "common/file_digest.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <system_error>
#include <tuple>
#include <vector>

#include "common/fnv_hash.h"

namespace peensim {

namespace {

// What a file was when it was read: a file rewritten since (another size or time) is read again.
using FileStamp = std::tuple<std::string, std::uintmax_t, std::filesystem::file_time_type>;

std::string digest_of_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return {};
    std::vector<char> chunk(std::size_t{1} << 20);
    std::uint64_t hash = kFnvOffsetBasis;
    std::uintmax_t size = 0;
    while (in) {
        in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
        const auto got = static_cast<std::size_t>(in.gcount());
        hash = fnv1a64({chunk.data(), got}, hash);
        size += got;
    }
    if (in.bad()) return {};
    char text[64];
    std::snprintf(text, sizeof text, "fnv1a64 %016llx, %llu B", static_cast<unsigned long long>(hash),
                  static_cast<unsigned long long>(size));
    return text;
}

}  // namespace

std::string file_digest_text(const std::string& path) {
    std::error_code error;
    const std::uintmax_t size = std::filesystem::file_size(path, error);
    const auto time = error ? std::filesystem::file_time_type{} : std::filesystem::last_write_time(path, error);
    if (error) return "unreadable " + path;
    static std::mutex mutex;
    static std::map<FileStamp, std::string> read;
    const FileStamp stamp{path, size, time};
    {
        const std::lock_guard<std::mutex> lock(mutex);
        if (const auto it = read.find(stamp); it != read.end()) return it->second;
    }
    std::string digest = digest_of_bytes(path);
    if (digest.empty()) return "unreadable " + path;
    const std::lock_guard<std::mutex> lock(mutex);
    return read.emplace(stamp, std::move(digest)).first->second;
}

}  // namespace peensim
