// The glyphs of the text overlay, rasterised once into one greyscale atlas image.
//
// Why FreeType with DejaVu Sans rather than a built-in bitmap font: the overlay must read well
// from a 160x120 test frame to a 1920x1080 video, which needs anti-aliased glyphs at any pixel
// size; a bitmap font is one size, blocky when scaled, and would mean shipping hand-made glyph
// tables. FreeType and DejaVu are standard Debian packages (libfreetype-dev, fonts-dejavu-core),
// and the cost is one atlas built when the renderer starts (a few ms), not per frame.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace peensim::render {

// Where DejaVu Sans is installed by Debian/Ubuntu (fonts-dejavu-core), Fedora and Arch; the
// first existing one, or nullopt.
std::optional<std::string> find_default_font();

// Printable ASCII (32..126); any other byte is drawn as '?'.
class FontAtlas {
public:
    struct Glyph {
        int x = 0, y = 0;           // px, top-left of its bitmap in the atlas
        int width = 0, height = 0;  // px, bitmap size
        int left = 0, top = 0;      // px, bitmap offset from the pen: right, and up from the baseline
        int advance = 0;            // px, pen move after the glyph
    };

    // Throws std::runtime_error naming the file if FreeType cannot load it or the size.
    FontAtlas(const std::string& font_path, int pixel_height);

    const Glyph& glyph(char c) const;
    int text_width(std::string_view text) const;  // px, sum of advances

    int pixel_height() const { return pixel_height_; }
    int ascender() const { return ascender_; }        // px, baseline to the top of tall glyphs
    int line_height() const { return line_height_; }  // px, baseline to baseline

    int width() const { return width_; }
    int height() const { return height_; }
    const std::vector<std::uint8_t>& pixels() const { return pixels_; }  // coverage 0..255, top row first
    // A 2x2 block of full coverage at the atlas origin: untextured shapes (the colour bar) use
    // it so that text and shapes share one draw call.
    static constexpr int kSolidBlock = 2;  // px, side of that block

private:
    static constexpr int kFirst = 32;
    static constexpr int kLast = 126;
    std::array<Glyph, kLast - kFirst + 1> glyphs_{};
    int pixel_height_ = 0;
    int ascender_ = 0;
    int line_height_ = 0;
    int width_ = 0;
    int height_ = 0;
    std::vector<std::uint8_t> pixels_;
};

}  // namespace peensim::render
