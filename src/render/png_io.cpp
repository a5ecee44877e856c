#include "render/png_io.h"

#include <png.h>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "output/atomic_file.h"

namespace peensim::render {

namespace {

constexpr int kZlibLevel = 1;  // fastest deflate; see the header for the measurement

struct PngErrorText {
    char text[256] = "unknown libpng error";
};

void on_png_error(png_structp png, png_const_charp message) {
    auto* error = static_cast<PngErrorText*>(png_get_error_ptr(png));
    std::snprintf(error->text, sizeof error->text, "%s", message);
    png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

void append_to_buffer(png_structp png, png_bytep data, png_size_t size) {
    auto* out = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(png));
    bool ok = true;
    try {
        out->insert(out->end(), data, data + size);
    } catch (...) {
        ok = false;
    }
    // Raised after the catch block has ended: the longjmp then leaves no live C++ object behind.
    if (!ok) png_error(png, "out of memory while encoding");
}

void flush_nothing(png_structp) {}

// Encodes into `out`. libpng reports errors by longjmp, so only trivially destructible locals
// live in this frame and the exception-safe work (file I/O) happens in the caller.
bool encode_png(const RgbaImage& image, bool opaque, std::vector<unsigned char>& out, PngErrorText& error) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, on_png_error, on_png_warning);
    if (png == nullptr) return false;
    png_infop info = png_create_info_struct(png);
    if (info == nullptr) {
        png_destroy_write_struct(&png, nullptr);
        return false;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_set_write_fn(png, &out, append_to_buffer, flush_nothing);
    png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
                 opaque ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
    png_set_compression_level(png, kZlibLevel);
    png_write_info(png, info);
    if (opaque) png_set_filler(png, 0, PNG_FILLER_AFTER);  // libpng drops the 4th byte of each pixel
    for (int y = 0; y < image.height; ++y) {
        png_write_row(png, image.pixels.data() + static_cast<std::size_t>(y) * image.row_bytes());
    }
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

}  // namespace

void write_png(const std::string& path, const RgbaImage& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4) {
        throw std::invalid_argument("write_png '" + path + "': image is empty or its pixel count does not match " +
                                    std::to_string(image.width) + "x" + std::to_string(image.height));
    }
    std::vector<unsigned char> bytes;
    bytes.reserve(image.pixels.size() / 4);  // a rendered frame compresses to roughly this
    bool opaque = true;
    for (std::size_t i = 3; i < image.pixels.size(); i += 4) opaque = opaque && image.pixels[i] == 255;
    PngErrorText error;
    if (!encode_png(image, opaque, bytes, error)) {
        throw std::runtime_error("cannot encode PNG '" + path + "': " + error.text);
    }
    write_file_atomically(path, {reinterpret_cast<const char*>(bytes.data()), bytes.size()}, Durability::process_crash);
}

RgbaImage read_png(const std::string& path) {
    png_image png;
    std::memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&png, path.c_str())) {
        throw std::runtime_error("cannot read PNG '" + path + "': " + png.message);
    }
    png.format = PNG_FORMAT_RGBA;
    RgbaImage image;
    image.resize(static_cast<int>(png.width), static_cast<int>(png.height));
    if (!png_image_finish_read(&png, nullptr, image.pixels.data(), 0, nullptr)) {
        png_image_free(&png);
        throw std::runtime_error("cannot read PNG '" + path + "': " + png.message);
    }
    return image;
}

}  // namespace peensim::render
