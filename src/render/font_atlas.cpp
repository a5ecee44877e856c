#include "render/font_atlas.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include <ft2build.h>
#include FT_FREETYPE_H

namespace peensim::render {

namespace {

constexpr int kAtlasWidth = 512;  // px; rows of glyphs are packed left to right
constexpr int kPadding = 1;       // px between glyphs, so neighbours never bleed in

struct LibraryDeleter {
    void operator()(FT_Library library) const { FT_Done_FreeType(library); }
};
struct FaceDeleter {
    void operator()(FT_Face face) const { FT_Done_Face(face); }
};

std::runtime_error font_error(const std::string& path, const std::string& what, FT_Error code) {
    return std::runtime_error("render: cannot " + what + " font '" + path + "' (FreeType error " + std::to_string(code) + ")");
}

}  // namespace

std::optional<std::string> find_default_font() {
    for (const char* candidate : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/dejavu/DejaVuSans.ttf",
                                  "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf", "/usr/share/fonts/TTF/DejaVuSans.ttf"}) {
        std::error_code ec;
        if (std::filesystem::is_regular_file(candidate, ec)) return std::string(candidate);
    }
    return std::nullopt;
}

FontAtlas::FontAtlas(const std::string& font_path, int pixel_height) : pixel_height_(pixel_height) {
    if (pixel_height < 4) throw std::invalid_argument("render: text height must be at least 4 px");
    FT_Library raw_library = nullptr;
    if (const FT_Error e = FT_Init_FreeType(&raw_library)) throw font_error(font_path, "start FreeType for", e);
    const std::unique_ptr<FT_LibraryRec_, LibraryDeleter> library(raw_library);
    FT_Face raw_face = nullptr;
    if (const FT_Error e = FT_New_Face(library.get(), font_path.c_str(), 0, &raw_face)) throw font_error(font_path, "load", e);
    const std::unique_ptr<FT_FaceRec_, FaceDeleter> face(raw_face);
    if (const FT_Error e = FT_Set_Pixel_Sizes(face.get(), 0, static_cast<FT_UInt>(pixel_height))) {
        throw font_error(font_path, "size", e);
    }
    ascender_ = static_cast<int>(face->size->metrics.ascender >> 6);
    line_height_ = static_cast<int>(face->size->metrics.height >> 6);

    // Each glyph is rendered twice: once to measure and place it, once to copy it in. That
    // keeps the code simple; 95 small glyphs take well under a millisecond.
    int pen_x = kSolidBlock + kPadding;
    int pen_y = 0;
    int row_height = kSolidBlock;
    for (int c = kFirst; c <= kLast; ++c) {
        if (const FT_Error e = FT_Load_Char(face.get(), static_cast<FT_ULong>(c), FT_LOAD_RENDER)) {
            throw font_error(font_path, "render glyph '" + std::string(1, static_cast<char>(c)) + "' of", e);
        }
        const FT_GlyphSlot slot = face->glyph;
        Glyph& g = glyphs_[static_cast<std::size_t>(c - kFirst)];
        g.width = static_cast<int>(slot->bitmap.width);
        g.height = static_cast<int>(slot->bitmap.rows);
        g.left = slot->bitmap_left;
        g.top = slot->bitmap_top;
        g.advance = static_cast<int>(slot->advance.x >> 6);
        if (pen_x + g.width > kAtlasWidth) {
            pen_x = 0;
            pen_y += row_height + kPadding;
            row_height = 0;
        }
        g.x = pen_x;
        g.y = pen_y;
        pen_x += g.width + kPadding;
        row_height = std::max(row_height, g.height);
    }
    width_ = kAtlasWidth;
    height_ = pen_y + row_height;
    pixels_.assign(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), 0);
    for (int y = 0; y < kSolidBlock; ++y) {
        for (int x = 0; x < kSolidBlock; ++x) pixels_[static_cast<std::size_t>(y * width_ + x)] = 255;
    }
    for (int c = kFirst; c <= kLast; ++c) {
        FT_Load_Char(face.get(), static_cast<FT_ULong>(c), FT_LOAD_RENDER);  // succeeded above
        const FT_Bitmap& bitmap = face->glyph->bitmap;
        const Glyph& g = glyphs_[static_cast<std::size_t>(c - kFirst)];
        for (int row = 0; row < g.height; ++row) {
            const unsigned char* src = bitmap.buffer + static_cast<std::ptrdiff_t>(row) * bitmap.pitch;
            std::copy(src, src + g.width, pixels_.begin() + static_cast<std::ptrdiff_t>((g.y + row) * width_ + g.x));
        }
    }
}

const FontAtlas::Glyph& FontAtlas::glyph(char c) const {
    const int code = static_cast<unsigned char>(c);
    return glyphs_[static_cast<std::size_t>((code >= kFirst && code <= kLast ? code : '?') - kFirst)];
}

int FontAtlas::text_width(std::string_view text) const {
    int w = 0;
    for (char c : text) w += glyph(c).advance;
    return w;
}

}  // namespace peensim::render
