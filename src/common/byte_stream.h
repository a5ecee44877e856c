// Plain values to bytes and back, for checkpoints: trivially copyable values in native byte
// order (little-endian: the static_assert keeps a big-endian build from writing other bytes),
// vectors and strings with a 64-bit length first. A reader that runs out of bytes throws
// std::runtime_error naming what it was reading ("<what>: truncated"), never reads past the end.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace peensim {

static_assert(std::endian::native == std::endian::little, "checkpoint bytes are little-endian");

class ByteWriter {
public:
    template <class T>
    void put(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T));
    }
    template <class T>
    void put_vector(const std::vector<T>& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        put<std::uint64_t>(v.size());
        if (!v.empty()) bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    }
    void put_string(std::string_view s) {
        put<std::uint64_t>(s.size());
        bytes_.append(s);
    }
    void put_raw(std::string_view s) { bytes_.append(s); }
    const std::string& bytes() const { return bytes_; }

private:
    std::string bytes_;
};

class ByteReader {
public:
    // `bytes` must outlive the reader; `what` names them in errors.
    ByteReader(std::string_view bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}

    template <class T>
    T get() {
        static_assert(std::is_trivially_copyable_v<T>);
        T v;
        std::memcpy(&v, take(sizeof(T)).data(), sizeof(T));
        return v;
    }
    template <class T>
    std::vector<T> get_vector() {
        const auto n = get<std::uint64_t>();
        if (n > (bytes_.size() - at_) / sizeof(T)) fail("truncated");
        std::vector<T> v(n);
        // An empty vector's data() may be null, which memcpy must not be given even for 0 bytes.
        if (n > 0) std::memcpy(v.data(), take(n * sizeof(T)).data(), n * sizeof(T));
        return v;
    }
    std::string get_string() { return std::string(take(get<std::uint64_t>())); }
    // The next n bytes as they are.
    std::string_view take(std::uint64_t n) {
        if (n > bytes_.size() - at_) fail("truncated");
        const std::string_view s = bytes_.substr(at_, n);
        at_ += n;
        return s;
    }
    bool at_end() const { return at_ == bytes_.size(); }
    std::size_t remaining() const { return bytes_.size() - at_; }

    [[noreturn]] void fail(const std::string& problem) const { throw std::runtime_error(what_ + ": " + problem); }

private:
    std::string_view bytes_;
    std::string what_;
    std::size_t at_ = 0;
};

}  // namespace peensim
