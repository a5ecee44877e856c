// PNG writing and reading: exact round trip, atomic replacement, plain errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "render/png_io.h"
#include "support/temp_dir.h"

namespace peensim::render {
namespace {

namespace fs = std::filesystem;

RgbaImage pattern(int w, int h) {
    RgbaImage image;
    image.resize(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = image.pixels.data() + (static_cast<std::size_t>(y) * w + x) * 4;
            p[0] = static_cast<std::uint8_t>(x * 7 + y);
            p[1] = static_cast<std::uint8_t>(y * 13);
            p[2] = static_cast<std::uint8_t>((x ^ y) * 3);
            p[3] = static_cast<std::uint8_t>(255 - x);  // alpha varies too: it must survive
        }
    }
    return image;
}

TEST(RenderPng, RoundTripKeepsSizeAndEveryPixel) {
    testing::TempDir dir;
    const RgbaImage image = pattern(37, 23);  // odd sizes: no row padding assumptions
    const std::string path = (dir.path / "frame.png").string();
    write_png(path, image);
    const RgbaImage back = read_png(path);
    EXPECT_EQ(back.width, 37);
    EXPECT_EQ(back.height, 23);
    EXPECT_EQ(back.pixels, image.pixels);
    EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST(RenderPng, TopRowComesFirst) {
    testing::TempDir dir;
    RgbaImage image;
    image.resize(2, 2);
    std::fill(image.pixels.begin(), image.pixels.end(), 0);
    image.pixels[0] = 255;  // red at (0, 0), the top-left pixel
    image.pixels[3] = 255;
    const std::string path = (dir.path / "corner.png").string();
    write_png(path, image);
    const RgbaImage back = read_png(path);
    EXPECT_EQ(back.at(0, 0), (Rgba8{255, 0, 0, 255}));
    EXPECT_EQ(back.at(0, 1), (Rgba8{0, 0, 0, 0}));
}

TEST(RenderPng, ReplacesAnExistingFile) {
    testing::TempDir dir;
    const std::string path = (dir.path / "frame.png").string();
    std::ofstream(path) << "old content";
    write_png(path, pattern(8, 8));
    EXPECT_EQ(read_png(path).pixels, pattern(8, 8).pixels);
}

TEST(RenderPng, MissingDirectoryIsAPlainErrorAndLeavesNothing) {
    testing::TempDir dir;
    const std::string path = (dir.path / "no-such-dir" / "frame.png").string();
    try {
        write_png(path, pattern(4, 4));
        FAIL() << "expected std::runtime_error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("no-such-dir"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::is_empty(dir.path));
}

TEST(RenderPng, RejectsAnInconsistentImage) {
    RgbaImage image;
    image.width = 4;
    image.height = 4;
    image.pixels.resize(10);
    EXPECT_THROW(write_png("/tmp/never-written.png", image), std::invalid_argument);
}

TEST(RenderPng, ReadingANonPngIsAPlainError) {
    testing::TempDir dir;
    const std::string path = (dir.path / "not.png").string();
    std::ofstream(path) << "this is not a PNG";
    EXPECT_THROW(read_png(path), std::runtime_error);
    EXPECT_THROW(read_png((dir.path / "missing.png").string()), std::runtime_error);
}

}  // namespace
}  // namespace peensim::render
