// An 8-bit RGBA image in memory, top row first (the order of PNG files and video frames).
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include "render/colour.h"

namespace peensim::render {

struct RgbaImage {
    int width = 0;                     // pixels
    int height = 0;                    // pixels
    std::vector<std::uint8_t> pixels;  // width * height * 4 bytes, row y at y * width * 4

    // Resizes without shrinking the allocation, so a reused image costs no allocation per frame.
    void resize(int w, int h) {
        width = w;
        height = h;
        pixels.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
    }
    std::size_t byte_size() const { return pixels.size(); }
    std::size_t row_bytes() const { return static_cast<std::size_t>(width) * 4; }

    // (x, y) from the top-left corner; no bounds check.
    Rgba8 at(int x, int y) const {
        Rgba8 c;
        std::memcpy(&c, pixels.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4,
                    4);
        return c;
    }
};

// Copies `tile` into `image` with its top-left corner at (x0, y0) (the tile must fit).
inline void blit(const RgbaImage& tile, RgbaImage& image, int x0, int y0) {
    for (int y = 0; y < tile.height; ++y)
        std::memcpy(image.pixels.data() +
                        (static_cast<std::size_t>(y0 + y) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x0)) * 4,
                    tile.pixels.data() + static_cast<std::size_t>(y) * tile.row_bytes(), tile.row_bytes());
}

}  // namespace peensim::render
