// FNV-1a, 64 bit: a fast hash of bytes for identity checks (a scene's simulated content, a
// checkpoint's checksum, pinned outputs in tests). Any single flipped bit changes it; not for
// security.
#pragma once

#include <cstdint>
#include <string_view>

namespace peensim {

inline constexpr std::uint64_t kFnvOffsetBasis = 14695981039346656037ull;

// Continues hash `h` over `bytes` (start from kFnvOffsetBasis).
inline std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t h = kFnvOffsetBasis) {
    for (unsigned char c : bytes) {
        h ^= c;
        h *= 1099511628211ull;
    }
    return h;
}

}  // namespace peensim
