// An OpenGL context that renders into memory (OSMesa, Mesa's llvmpipe rasteriser on the CPU),
// so frames can be made on a machine without a display or a GPU.
#pragma once

#include <cstdint>
#include <vector>

#include "render/image.h"

struct osmesa_context;  // OSMesa's context handle, kept out of this header

namespace peensim::render {

struct ContextOptions {
    int width = 1280;  // pixels
    int height = 720;  // pixels
    // Multisample anti-aliasing: 0 (off) or 2..4 samples per pixel, resolved in read_pixels.
    // Smooths the silhouettes of shot and walls at a cost measured in render_bench.cpp.
    int samples = 0;
};

// Owns the context and its framebuffer and makes it current in the constructing thread.
// Several contexts may coexist (each frame size needs its own); call make_current() before
// drawing into one that is not current. Not thread-safe: use a context from one thread.
//
// llvmpipe's thread count: unless LP_NUM_THREADS is already set, the first context sets it to 1
// (setenv, before Mesa reads it). Measured with render_bench.cpp on 2 cores: rendering while
// ffmpeg encodes the video (the recording case) ran at 25-29 frames/s with one rasteriser
// thread, 22-24 with two; rendering alone, two threads won only when the second core was idle
// (best frames ~25 % faster, medians within noise when other work ran), and the simulation
// itself needs that core.
class OffscreenContext {
public:
    // Throws std::runtime_error with a plain message if OSMesa cannot create the context
    // (for example a Mesa without OSMesa or without OpenGL 3.3), std::invalid_argument for a
    // non-positive size or an unsupported sample count.
    explicit OffscreenContext(const ContextOptions& options);
    ~OffscreenContext();
    OffscreenContext(const OffscreenContext&) = delete;
    OffscreenContext& operator=(const OffscreenContext&) = delete;

    int width() const { return width_; }
    int height() const { return height_; }
    int samples() const { return samples_; }

    void make_current();

    // Binds the framebuffer that frames are drawn into (the multisample one when samples > 0)
    // and sets the viewport to the whole image.
    void bind_draw_target();

    // Waits for the frame to finish and copies it into `image` (resized to width x height,
    // top row first). Reusing one image makes this allocation-free.
    void read_pixels(RgbaImage& image);

private:
    osmesa_context* context_ = nullptr;
    int width_ = 0;
    int height_ = 0;
    int samples_ = 0;
    std::vector<std::uint8_t> colour_buffer_;  // OSMesa's framebuffer (bottom row first)
    unsigned int msaa_framebuffer_ = 0;
    unsigned int msaa_colour_ = 0;
    unsigned int msaa_depth_ = 0;
};

}  // namespace peensim::render
