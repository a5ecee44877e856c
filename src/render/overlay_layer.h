// The 2-D layer drawn over the scene in pixel coordinates: lines of text at the top left and a
// colour bar with its labels at the right. Everything is one textured triangle list (glyphs
// from the font atlas; shapes use its solid block), so the layer costs one draw call.
// Internal to render/.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "render/font_atlas.h"
#include "render/gl_objects.h"
#include "render/scene_types.h"

namespace peensim::render {

class OverlayLayer {
public:
    // Uploads the atlas; needs the target context current.
    explicit OverlayLayer(FontAtlas atlas);

    // Draws over whatever the frame holds (no depth test). `bar` may be null.
    void draw(int width, int height, std::span<const std::string> lines, const ColourBar* bar, std::span<const Label> labels = {});

    const FontAtlas& atlas() const { return atlas_; }

private:
    struct Vertex {
        float x, y;  // px from the top-left corner
        float u, v;  // atlas texture coordinates
        Rgba8 colour;
    };
    void add_quad(float x0, float y0, float x1, float y1, float u0, float v0, float u1, float v1, Rgba8 top, Rgba8 bottom);
    void add_solid(float x0, float y0, float x1, float y1, Rgba8 top, Rgba8 bottom);
    void add_text(float x, float baseline, std::string_view text, Rgba8 colour);
    void add_shadowed_text(float x, float baseline, std::string_view text);
    void add_colour_bar(int width, int height, const ColourBar& bar);
    void add_mark(int width, const ColourBar& bar, float x0, float x1, float top, float bottom);

    FontAtlas atlas_;
    gl::Program program_;
    GLint u_viewport_ = -1, u_atlas_ = -1;
    gl::Texture texture_;
    gl::VertexArray vao_;
    gl::Buffer buffer_;
    std::size_t buffer_capacity_ = 0;  // vertices the GL buffer holds
    std::vector<Vertex> vertices_;     // staging, reused
    char label_[32] = {};              // formatted number, reused
};

}  // namespace peensim::render
