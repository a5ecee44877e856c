#include "render/offscreen_context.h"

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include "render/gl.h"

namespace peensim::render {

namespace {

// GL 3.3: instancing, texture buffers and gl_PrimitiveID, which the scene renderer uses.
constexpr int kGlMajor = 3;
constexpr int kGlMinor = 3;

bool has_extension(const char* name) {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
        const auto* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
        if (e != nullptr && std::strcmp(e, name) == 0) return true;
    }
    return false;
}

}  // namespace

OffscreenContext::OffscreenContext(const ContextOptions& options)
    : width_(options.width), height_(options.height), samples_(options.samples) {
    if (width_ <= 0 || height_ <= 0) {
        throw std::invalid_argument("render: image size must be positive, got " + std::to_string(width_) + "x" + std::to_string(height_));
    }
    if (samples_ < 0 || samples_ == 1 || samples_ > 16) {
        throw std::invalid_argument("render: samples must be 0 (off) or 2..16, got " + std::to_string(samples_));
    }
    ::setenv("LP_NUM_THREADS", "1", /*overwrite=*/0);

    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_COMPAT_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              kGlMajor,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              kGlMinor,
                              0};
    context_ = OSMesaCreateContextAttribs(attributes, nullptr);
    if (context_ == nullptr) {
        throw std::runtime_error("render: OSMesa could not create an OpenGL " + std::to_string(kGlMajor) + "." + std::to_string(kGlMinor) +
                                 " context (is Mesa's libOSMesa with llvmpipe installed?)");
    }
    colour_buffer_.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 4);
    if (!OSMesaMakeCurrent(context_, colour_buffer_.data(), GL_UNSIGNED_BYTE, width_, height_)) {
        OSMesaDestroyContext(context_);
        throw std::runtime_error("render: OSMesa could not bind a " + std::to_string(width_) + "x" + std::to_string(height_) +
                                 " framebuffer (too large?)");
    }
    // Every Mesa driver has it (it is one of Mesa's always-on extensions); checked anyway so
    // that a strange build fails here with a message instead of writing upside-down frames.
    if (!has_extension("GL_MESA_pack_invert")) {
        OSMesaDestroyContext(context_);
        throw std::runtime_error("render: this OSMesa lacks GL_MESA_pack_invert (needed to read frames top row first)");
    }

    if (samples_ > 0) {
        GLint max_samples = 0;
        glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
        if (samples_ > max_samples) {
            OSMesaDestroyContext(context_);
            throw std::invalid_argument("render: " + std::to_string(samples_) + " samples requested, this OpenGL offers at most " +
                                        std::to_string(max_samples));
        }
        glGenFramebuffers(1, &msaa_framebuffer_);
        glGenRenderbuffers(1, &msaa_colour_);
        glGenRenderbuffers(1, &msaa_depth_);
        glBindRenderbuffer(GL_RENDERBUFFER, msaa_colour_);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_RGBA8, width_, height_);
        glBindRenderbuffer(GL_RENDERBUFFER, msaa_depth_);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_DEPTH_COMPONENT24, width_, height_);
        glBindFramebuffer(GL_FRAMEBUFFER, msaa_framebuffer_);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaa_colour_);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaa_depth_);
        const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            OSMesaDestroyContext(context_);
            throw std::runtime_error("render: the multisample framebuffer is incomplete (status " + std::to_string(status) + ")");
        }
    }
    bind_draw_target();
}

OffscreenContext::~OffscreenContext() {
    if (context_ == nullptr) return;
    make_current();
    if (msaa_framebuffer_ != 0) {
        glDeleteFramebuffers(1, &msaa_framebuffer_);
        glDeleteRenderbuffers(1, &msaa_colour_);
        glDeleteRenderbuffers(1, &msaa_depth_);
    }
    OSMesaDestroyContext(context_);
}

void OffscreenContext::make_current() {
    if (OSMesaGetCurrentContext() == context_) return;
    if (!OSMesaMakeCurrent(context_, colour_buffer_.data(), GL_UNSIGNED_BYTE, width_, height_)) {
        throw std::runtime_error("render: OSMesa could not make the context current");
    }
}

void OffscreenContext::bind_draw_target() {
    glBindFramebuffer(GL_FRAMEBUFFER, msaa_framebuffer_);
    glViewport(0, 0, width_, height_);
}

void OffscreenContext::read_pixels(RgbaImage& image) {
    image.resize(width_, height_);
    if (msaa_framebuffer_ != 0) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, msaa_framebuffer_);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    // GL's rows start at the bottom, images at the top: GL_MESA_pack_invert flips while it
    // copies (measured: no slower than the plain read, ~1 ms at 1280x720).
    glPixelStorei(GL_PACK_INVERT_MESA, GL_TRUE);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
    glPixelStorei(GL_PACK_INVERT_MESA, GL_FALSE);
    bind_draw_target();
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        throw std::runtime_error("render: OpenGL error " + std::to_string(error) + " while reading the frame");
    }
}

}  // namespace peensim::render
