// Colour values of the renderer: RGBA in [0, 1] for styles, packed 8-bit RGBA for per-triangle
// and per-instance arrays (what the GPU reads, four bytes each).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace peensim::render {

// Components in [0, 1]; alpha 1 is opaque.
struct Rgba {
    float r = 0.0f, g = 0.0f, b = 0.0f, a = 1.0f;
};

// Components in 0..255, byte order R, G, B, A in memory (GL_RGBA8).
struct Rgba8 {
    std::uint8_t r = 0, g = 0, b = 0, a = 255;
    friend bool operator==(const Rgba8&, const Rgba8&) = default;
};
static_assert(sizeof(Rgba8) == 4, "Rgba8 must be four packed bytes");

inline std::uint8_t to_byte(float v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }
inline Rgba8 to_rgba8(const Rgba& c) { return {to_byte(c.r), to_byte(c.g), to_byte(c.b), to_byte(c.a)}; }
inline Rgba to_rgba(const Rgba8& c) {
    return {static_cast<float>(c.r) / 255.0f, static_cast<float>(c.g) / 255.0f, static_cast<float>(c.b) / 255.0f,
            static_cast<float>(c.a) / 255.0f};
}

}  // namespace peensim::render
